// survey.json: parsing (with the manifest's plausibility rules) and writing.
#include "survey/survey_manifest.h"

#include <algorithm>
#include <cmath>

#include "base/csv.h"
#include "survey/survey_plausibility.h"

namespace hull::survey_manifest {
namespace {

Vector6d ToVector6(const std::vector<double>& v) { return Eigen::Map<const Vector6d>(v.data()); }
Eigen::Vector3d ToVector3(const std::vector<double>& v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

}  // namespace

Json Vec(const Eigen::VectorXd& v) {
  Json a = Json::Array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.Push(Json(v[i]));
  return a;
}

void CheckPositive(const JsonReader& r, std::string_view key, double v) {
  if (!(v > 0)) r.Fail(r.Required(key), key, "expected a positive number, got " + FormatDouble(v));
}

namespace {

// A number within [lo, hi], with the reason the bound exists.
void CheckRange(const JsonReader& r, std::string_view key, double v, double lo, double hi, const std::string& why) {
  if (!(v >= lo && v <= hi)) {
    r.Fail(r.Required(key), key,
           FormatDouble(v) + " is not plausible: expected " + FormatDouble(lo) + " to " + FormatDouble(hi) + " (" +
               why + ")");
  }
}

// Intrinsics within the image's scale (plausibility.h: focal lengths and
// principal point against the image size).
PinholeIntrinsics ReadIntrinsics(const JsonReader& r, int width, int height) {
  PinholeIntrinsics k;
  const double size = std::max(width, height);
  const std::string focal_why = "a focal length is " + FormatDouble(plausible::kMinFocalPerImage) + " to " +
                                FormatDouble(plausible::kMaxFocalPerImage) +
                                " times the image's larger side, from a 175 deg fisheye to a 0.6 deg telephoto";
  k.fx = r.Number("fx");
  CheckPositive(r, "fx", k.fx);
  CheckRange(r, "fx", k.fx, plausible::kMinFocalPerImage * size, plausible::kMaxFocalPerImage * size, focal_why);
  k.fy = r.Number("fy");
  CheckPositive(r, "fy", k.fy);
  CheckRange(r, "fy", k.fy, plausible::kMinFocalPerImage * size, plausible::kMaxFocalPerImage * size, focal_why);
  k.cx = r.Number("cx");
  CheckRange(r, "cx", k.cx, -width, 2.0 * width, "the principal point lies near the image, within one image size");
  k.cy = r.Number("cy");
  CheckRange(r, "cy", k.cy, -height, 2.0 * height, "the principal point lies near the image, within one image size");
  return k;
}

// A fixed transform [x, y, z, roll, pitch, yaw] on the vehicle: a lever arm
// within kMaxLeverArm and angles within one turn (rotations are given as
// angles only, so they are orthonormal by construction; the bound catches
// degrees written as radians and corrupt values, whose sines are noise).
Vector6d ReadMountPose(const JsonReader& r, std::string_view key, double max_offset,
                       const char* what = "a sensor's lever arm on the vehicle") {
  const Vector6d x = ToVector6(r.Numbers(key, 6));
  if (!(x.head<3>().norm() <= max_offset)) {
    r.Fail(r.Required(key), key,
           "offset of " + FormatDouble(x.head<3>().norm()) + " m is not plausible: expected at most " +
               FormatDouble(max_offset) + " m (" + what + ")");
  }
  for (int i = 3; i < 6; ++i) {
    if (!(std::abs(x[i]) <= plausible::kMaxFixedAngle)) {
      r.Fail(r.Required(key), key,
             "angle " + FormatDouble(x[i]) +
                 " rad is not plausible: expected at most 2 pi in magnitude (angles are "
                 "radians; a fixed rotation needs no more than one turn)");
    }
  }
  return x;
}

}  // namespace

Eigen::Vector3d NonZero3(const JsonReader& r, std::string_view key) {
  Eigen::Vector3d v = ToVector3(r.Numbers(key, 3));
  if (v.norm() < 1e-12) r.Fail(r.Required(key), key, "expected a non-zero direction");
  return v;
}

namespace {

// camera.type, width and height: a known type and a size some camera has.
void ReadCameraTypeAndSize(const JsonReader& cam, CameraRig& camera) {
  const std::string type = cam.String("type");
  if (type == "stereo") {
    camera.type = CameraType::kStereo;
  } else if (type == "mono") {
    camera.type = CameraType::kMono;
  } else {
    cam.Fail(cam.Required("type"), "type", "expected \"stereo\" or \"mono\", got \"" + type + "\"");
  }
  const std::int64_t w = cam.Integer("width"), h = cam.Integer("height");
  if (w <= 0) cam.Fail(cam.Required("width"), "width", "expected a positive integer");
  if (h <= 0) cam.Fail(cam.Required("height"), "height", "expected a positive integer");
  if (w > plausible::kMaxImageSide) {
    cam.Fail(cam.Required("width"), "width",
             "expected at most " + std::to_string(plausible::kMaxImageSide) + " pixels");
  }
  if (h > plausible::kMaxImageSide) {
    cam.Fail(cam.Required("height"), "height",
             "expected at most " + std::to_string(plausible::kMaxImageSide) + " pixels");
  }
  if (w * h > plausible::kMaxImagePixels) {
    cam.Fail(cam.Required("width"), "width",
             std::to_string(w) + " x " + std::to_string(h) + " pixels is " + std::to_string(w * h / 1000000) +
                 " megapixels; expected at most " + std::to_string(plausible::kMaxImagePixels / 1000000) +
                 " (no survey camera has more)");
  }
  camera.width = static_cast<int>(w);
  camera.height = static_cast<int>(h);
}

}  // namespace

SurveyManifest ParseManifest(const Json& doc, const std::string& file) {
  JsonReader root(doc, file);
  SurveyManifest m;
  const std::string format = root.String("format");
  if (format != "hull-survey") {
    root.Fail(root.Required("format"), "format", "expected \"hull-survey\", got \"" + format + "\"");
  }
  const std::int64_t version = root.Integer("version");
  if (version != 1 && version != 2) {
    root.Fail(root.Required("version"), "version",
              "unsupported version " + std::to_string(version) + "; this reader knows versions 1 and 2");
  }
  m.version = static_cast<int>(version);
  m.name = root.OptionalString("name").value_or("");
  m.vehicle = root.OptionalString("vehicle").value_or("");
  m.model_hint = root.OptionalString("model_hint");
  if (m.model_hint && m.model_hint->empty()) root.Fail(root.Required("model_hint"), "model_hint", "empty path");

  const JsonReader cam = root.Object("camera");
  ReadCameraTypeAndSize(cam, m.camera);
  m.camera.top = ReadIntrinsics(cam.Object("top"), m.camera.width, m.camera.height);
  if (m.camera.stereo()) {
    m.camera.bottom = ReadIntrinsics(cam.Object("bottom"), m.camera.width, m.camera.height);
    m.camera.top_to_bottom = ReadMountPose(cam, "top_to_bottom", plausible::kMaxLeverArm);
  } else {
    m.camera.bottom = m.camera.top;
    m.camera.top_to_bottom.setZero();
  }
  m.camera.servo_to_top = ReadMountPose(cam, "servo_to_top", plausible::kMaxLeverArm);

  m.servo_mount = ReadMountPose(root.Object("servo"), "mount", plausible::kMaxLeverArm);

  const JsonReader dvl = root.Object("dvl");
  m.servo_to_dvl = ReadMountPose(dvl, "servo_to_dvl", plausible::kMaxLeverArm);
  const Json& beams = dvl.Required("beams");
  if (!beams.is_array() || beams.items().size() != 4) {
    dvl.Fail(beams, "beams", "expected an array of 4 beam directions (Janus DVL, in the order r1..r4)");
  }
  for (int i = 0; i < 4; ++i) {
    const Json& b = beams.items()[static_cast<std::size_t>(i)];
    const std::string key = "beams[" + std::to_string(i) + "]";
    if (!b.is_array() || b.items().size() != 3) dvl.Fail(b, key, "expected 3 numbers");
    for (int k = 0; k < 3; ++k) {
      const Json& c = b.items()[static_cast<std::size_t>(k)];
      if (!c.is_number()) dvl.Fail(c, key, "expected a number");
      m.beams[static_cast<std::size_t>(i)][k] = c.as_number();
    }
    if (m.beams[static_cast<std::size_t>(i)].norm() < 1e-12) dvl.Fail(b, key, "expected a non-zero direction");
  }

  if (root.Has("model_pose_guess")) {
    m.model_pose_guess =
        ReadMountPose(root, "model_pose_guess", plausible::kMaxCoordinate, "no survey coordinate exceeds 1e7 m");
  }
  if (auto ax = root.OptionalObject("model_axes")) {
    ModelAxes a;
    a.forward = NonZero3(*ax, "forward").normalized();
    a.up = NonZero3(*ax, "up").normalized();
    if (std::abs(a.forward.dot(a.up)) > 0.99) {
      ax->Fail(ax->Required("up"), "up", "expected a direction not parallel to forward");
    }
    m.model_axes = a;
  }
  if (auto im = root.OptionalObject("images")) {
    ImagingNote note;
    if (im->Has("exposure_s")) {
      note.exposure_s = im->Number("exposure_s");
      CheckPositive(*im, "exposure_s", *note.exposure_s);
    }
    note.illumination = im->OptionalString("illumination");
    m.imaging = note;
  }
  if (auto nz = root.OptionalObject("noise")) {
    NoiseModel& n = m.noise;
    const double image = std::max(m.camera.width, m.camera.height);
    for (const plausible::SigmaBound& it : plausible::NoiseBounds(image)) {
      if (!nz->Has(it.key)) continue;
      double& value = plausible::NoiseField(n, it.key);
      value = nz->Number(it.key);
      CheckPositive(*nz, it.key, value);
      CheckRange(*nz, it.key, value, it.lo, it.hi, it.why);
    }
    if (auto s = nz->OptionalNumbers("servo_to_top_sigma", 6)) {
      for (int i = 0; i < 6; ++i) {
        const double v = (*s)[static_cast<std::size_t>(i)];
        const double hi = i < 3 ? plausible::kMaxLeverArm : M_PI;
        if (!(v > 0) || !(v <= hi)) {
          nz->Fail(nz->Required("servo_to_top_sigma"), "servo_to_top_sigma",
                   "expected 6 positive numbers, the first three at most " + FormatDouble(plausible::kMaxLeverArm) +
                       " m and the angles at most pi rad (an uncertainty beyond that is no prior); entry " +
                       std::to_string(i + 1) + " is " + FormatDouble(v));
        }
      }
      n.servo_to_top_sigma = ToVector6(*s);
    }
  }
  return m;
}

Json ManifestJson(const SurveyManifest& m) {
  Json root = Json::Object();
  root.Set("format", "hull-survey");
  root.Set("version", m.version);
  if (!m.name.empty()) root.Set("name", m.name);
  if (!m.vehicle.empty()) root.Set("vehicle", m.vehicle);
  if (m.model_hint) root.Set("model_hint", *m.model_hint);
  auto intr = [](const PinholeIntrinsics& k) {
    Json j = Json::Object();
    j.Set("fx", k.fx);
    j.Set("fy", k.fy);
    j.Set("cx", k.cx);
    j.Set("cy", k.cy);
    return j;
  };
  Json cam = Json::Object();
  cam.Set("type", m.camera.stereo() ? "stereo" : "mono");
  cam.Set("width", m.camera.width);
  cam.Set("height", m.camera.height);
  cam.Set("top", intr(m.camera.top));
  if (m.camera.stereo()) {
    cam.Set("bottom", intr(m.camera.bottom));
    cam.Set("top_to_bottom", Vec(m.camera.top_to_bottom));
  }
  cam.Set("servo_to_top", Vec(m.camera.servo_to_top));
  root.Set("camera", cam);
  Json servo = Json::Object();
  servo.Set("mount", Vec(m.servo_mount));
  root.Set("servo", servo);
  Json dvl = Json::Object();
  dvl.Set("servo_to_dvl", Vec(m.servo_to_dvl));
  Json beams = Json::Array();
  for (const auto& b : m.beams) beams.Push(Vec(b));
  dvl.Set("beams", beams);
  root.Set("dvl", dvl);
  if (m.model_pose_guess) root.Set("model_pose_guess", Vec(*m.model_pose_guess));
  if (m.model_axes) {
    Json ax = Json::Object();
    ax.Set("forward", Vec(m.model_axes->forward));
    ax.Set("up", Vec(m.model_axes->up));
    root.Set("model_axes", ax);
  }
  const NoiseModel& n = m.noise;
  Json nz = Json::Object();
  nz.Set("pixel_sigma", n.pixel_sigma);
  nz.Set("dvl_range_sigma", n.dvl_range_sigma);
  nz.Set("depth_sigma", n.depth_sigma);
  nz.Set("roll_pitch_sigma", n.roll_pitch_sigma);
  nz.Set("servo_sigma", n.servo_sigma);
  nz.Set("odometry_translation_rate", n.odometry_translation_rate);
  nz.Set("odometry_rotation_rate", n.odometry_rotation_rate);
  nz.Set("model_pose_sigma", n.model_pose_sigma);
  nz.Set("servo_to_top_sigma", Vec(n.servo_to_top_sigma));
  root.Set("noise", nz);
  if (m.imaging) {
    Json im = Json::Object();
    if (m.imaging->exposure_s) im.Set("exposure_s", *m.imaging->exposure_s);
    if (m.imaging->illumination) im.Set("illumination", *m.imaging->illumination);
    root.Set("images", im);
  }
  return root;
}

}  // namespace hull::survey_manifest
