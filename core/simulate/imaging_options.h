// The underwater camera's photometric options (strobes, water, sensor):
// what the renderer (image_renderer.h) images with and what the photomosaic
// (mosaic/photomosaic.h) inverts. Plain data: no Embree, no OpenCV.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace hull {

// A strobe (the HAUV's 520 nm LED) on the sensor tray.
struct Strobe {
  Eigen::Vector3d position = Eigen::Vector3d(0.25, 0.05, -0.05);  // m, in the top camera's frame cT
  Eigen::Vector3d axis = Eigen::Vector3d(-0.25, 0.0, 1.55);       // pointing direction in cT (normalised on use)
  double half_power_angle_deg = 40.0;                             // beam intensity halves this far off the axis
  double intensity = 1.0;                                         // relative to the other strobes
};

struct UnderwaterImagingOptions {
  double attenuation = 0.3;     // c, 1/m: Beer-Lambert attenuation on every light path (harbour water at 520 nm)
  double backscatter = 0.0015;  // 1/(m sr): strobe light the water scatters back toward the camera
  std::vector<Strobe> strobes = {Strobe{}};
  bool shadows = true;          // strobe shadows (one shadow ray per pixel and strobe)
  double exposure_level = 0.8;  // share of full scale reached by albedo 0.5 facing the camera on its axis ...
  double exposure_range = 1.5;  // ... at this range (m): sets the fixed gain (no auto-exposure)
  double vignetting = 1.0;      // exponent on the natural cos^4 fall-off (0: none)
  double full_well = 12000;     // electrons at full scale (shot noise)
  double read_noise = 8;        // electrons rms
  double max_range = 12;        // m: rays that hit nothing within this see only open water
  double image_dropout = 0;     // simulator: probability that an image is missing (a dropped frame)
  int png_compression = 1;      // zlib level of the written PNGs (1: fastest)

  void Check() const;  // throws OptionError naming the field
};

}  // namespace hull
