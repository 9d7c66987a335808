// hullinspect-cli info: summarise a survey bundle, acoustic sequence or mesh.
#include <cstdio>
#include <filesystem>
#include <set>

#include "cli/args.h"
#include "cli/commands.h"
#include "geometry/mesh_io.h"
#include "survey/acoustic_sequence.h"
#include "survey/survey_images.h"
#include "survey/survey_import.h"
#include "survey/survey_io.h"

namespace hull::cli {
namespace {

const char* kHelp = R"(usage: hullinspect-cli info PATH [--mesh-scale S]

Summarises a survey bundle (folder with survey.json), an acoustic sequence
(folder with sonar.json) or a mesh file (STL, PLY, OBJ, OFF, glTF, ... also
.gz; STEP and IGES through the step-iges plugin, which also reports the
file's unit, surface count and tessellation), or a survey a plugin converts.
--mesh-scale applies a scale to a mesh on load (e.g. 59.4 for the DTC model), as
in every command that reads a mesh (--scale, its former name, is still accepted).
--quiet is accepted, as by every command (info prints no progress).
)";

void BundleInfo(const SurveyBundle& b) {
  const auto& m = b.manifest;
  std::printf("survey bundle   %s\n", b.directory.c_str());
  std::printf("name            %s\n", m.name.c_str());
  std::printf("vehicle         %s\n", m.vehicle.c_str());
  std::printf("camera          %s %dx%d, fx %.1f fy %.1f\n", m.camera.stereo() ? "stereo" : "mono", m.camera.width,
              m.camera.height, m.camera.top.fx, m.camera.top.fy);
  std::printf("model hint      %s\n", m.model_hint ? m.model_hint->c_str() : "(none)");
  std::printf("model pose      %s\n", m.model_pose_guess ? "guess given" : "none: align DVL returns (GICP)");
  const double span = b.nav.empty() ? 0.0 : b.nav.back().t - b.nav.front().t;
  std::printf("keyframes       %zu over %.1f s\n", b.nav.size(), span);
  std::printf("odometry        %zu links\n", b.odometry.size());
  std::size_t returns = 0;
  for (const auto& d : b.dvl) {
    for (double r : d.range) returns += DvlRecord::HasReturn(r);
  }
  std::printf("DVL             %zu rows, %zu of %zu beams returned\n", b.dvl.size(), returns, 4 * b.dvl.size());
  std::printf("features        %zu observations of %zu landmarks\n", b.features.size(), b.CountLandmarks());
  std::printf("landmarks.csv   %s\n", b.landmarks ? "present" : "absent (triangulated from the initial poses)");
  if (b.truth) {
    std::printf("truth           %zu poses, %zu landmarks, %zu objects\n", b.truth->poses.size(),
                b.truth->landmarks.size(), b.truth->objects.size());
  } else {
    std::printf("truth           absent\n");
  }
  if (b.sonar) std::printf("sonar           %d steps\n", b.sonar->num_steps());
  std::printf("format          version %d\n", m.version);
  if (b.images) {
    std::printf("images          %d of %d present, %d dropped frames\n", b.images->present(), b.images->expected,
                b.images->dropped);
    for (const KeyframeImages& k : b.images->frames) {
      if (k.top.empty()) continue;
      // The first image's header (the validator checks every image).
      const ImageInfo info = InspectImageFile(b.ImagePath(k.keyframe), SurveyImageRequirements(m));
      std::printf("image format    %s (%s, the first)\n", info.Describe().c_str(), k.top.c_str());
      break;
    }
    if (m.imaging && m.imaging->illumination) {
      std::printf("illumination    %s", m.imaging->illumination->c_str());
      if (m.imaging->exposure_s) std::printf(", exposure %.4g s", *m.imaging->exposure_s);
      std::printf("\n");
    }
  } else if (m.version >= 2) {
    std::printf("images          none (no images/ folder)\n");
  }
}

void SequenceInfo(const AcousticSequence& s, const std::string& path) {
  std::set<std::int64_t> features;
  for (const auto& m : s.measurements) features.insert(m.feature);
  std::printf("acoustic sequence %s\n", path.c_str());
  std::printf("steps           %d\n", s.num_steps());
  std::printf("features        %zu, measurements %zu\n", features.size(), s.measurements.size());
  std::printf("sensor          range %.2f..%.2f m, azimuth fov %.1f deg, elevation fov %.1f deg\n", s.sensor.range_min,
              s.sensor.range_max, s.sensor.azimuth_fov * 180 / M_PI, s.sensor.elevation_fov * 180 / M_PI);
  std::printf("truth           %s\n", s.truth ? "present" : "absent");
  if (s.image) {
    std::printf("images          %d range bins x %d beams (version 2)%s\n", s.image->range_bins, s.image->beams,
                s.has_measurements ? "" : ", no measurements.csv");
  }
}

// What an importer plugin reported (unit, surface count, ...).
void PrintImportReport(const std::vector<std::pair<std::string, std::string>>& report) {
  for (const auto& [key, value] : report) std::printf("%-15s %s\n", key.c_str(), value.c_str());
}

void MeshInfo(const std::string& path, double scale) {
  MeshLoadOptions lo;
  lo.scale = scale;
  OrientationReport rep;
  lo.orientation = &rep;
  std::vector<std::pair<std::string, std::string>> report;
  lo.import_report = &report;
  const TriangleMesh m = LoadMesh(path, lo);
  PrintImportReport(report);
  const auto box = m.Bounds();
  std::printf("mesh            %s\n", path.c_str());
  std::printf("vertices        %zu\n", m.num_vertices());
  std::printf("triangles       %zu\n", m.num_faces());
  std::printf("bounds          [%.3f %.3f %.3f] .. [%.3f %.3f %.3f]\n", box.min().x(), box.min().y(), box.min().z(),
              box.max().x(), box.max().y(), box.max().z());
  std::printf("size            %.3f x %.3f x %.3f\n", box.sizes().x(), box.sizes().y(), box.sizes().z());
  std::printf("area            %.3f\n", m.SurfaceArea());
  std::printf("closed          %s (%d boundary edges, %d non-manifold edges, %d components)\n",
              rep.closed ? "yes" : "no", rep.boundary_edges, rep.non_manifold_edges, rep.components);
  if (rep.closed) std::printf("volume          %.3f\n", m.SignedVolume());
  std::printf("orientation     %s%s\n", rep.faces_flipped ? "fixed: " : "consistent, outward",
              rep.faces_flipped ? (std::to_string(rep.faces_flipped) + " faces flipped").c_str() : "");
  for (const auto& [name, values] : m.vertex_scalars) std::printf("vertex scalar   %s\n", name.c_str());
}

}  // namespace

int RunInfo(const CommandArgs& argv) {
  Args a(argv, {"quiet"});
  if (a.Has("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  a.AllowOnly({"mesh-scale", "scale", "quiet"});
  if (a.positionals().size() != 1) throw UsageError("expected one path");
  const std::string path = a.positionals()[0];
  namespace fs = std::filesystem;
  if (fs::is_directory(path) && fs::exists(fs::path(path) / "sonar.json")) {
    SequenceInfo(ReadAcousticSequence(path), path);
  } else if (fs::is_directory(path) || (!IsMeshFile(path) && IsSurveyPath(path))) {
    // A bundle folder, or a survey log a plugin converts into one.
    std::vector<std::pair<std::string, std::string>> report;
    const SurveyBundle bundle = OpenSurveyBundle(path, &report);
    PrintImportReport(report);
    BundleInfo(bundle);
  } else {
    MeshInfo(path, a.GetDouble("mesh-scale", a.GetDouble("scale", 1.0)));  // --scale: the old name
  }
  return kExitOk;
}

}  // namespace hull::cli
