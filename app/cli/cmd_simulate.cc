// hullinspect-cli simulate: write a simulated survey bundle with truth.
#include <cstdio>
#include <sstream>

#include "base/csv.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/console_progress.h"
#include "simulate/sonar_image_simulator.h"
#include "simulate/sonar_simulator.h"
#include "simulate/survey_simulator.h"
#include "survey/acoustic_sequence.h"

namespace hull::cli {
namespace {

const char* kHelp = R"(usage: hullinspect-cli simulate --preset NAME --out DIR [options]

Writes a survey bundle (version 1) with ground truth in truth/: an HAUV
surveying a hull with foreign structure (biofouling patches, a cylinder, a
box), stereo or monocular camera, four-beam DVL, drifting odometry.
Deterministic from --seed. With --images, a version 2 bundle: the same plus
every keyframe's camera images (images/<keyframe>_top.png, _bottom.png; 8-bit
grey, strobe-lit, rendered from the truth) and truth/scene.ply (the true
surface in M) with truth/albedo.json (its albedo, for scoring).

presets:
  demo       stretch of hull bottom around the keel, stereo, ~300 keyframes
  mono       the same with a monocular camera (and ~3 % wrong matches)
  curtiss    full bottom and sides of the 183 m SS Curtiss-size hull, >= 10,000 keyframes
  sonar-prism, sonar-tank, sonar-above
             an acoustic sequence (imaging sonar) instead: the paper's square
             prism seen from 21 viewpoints, its tank layout (tilted 20 deg,
             rolled 0..70 deg), or a sonar 0.5 m above the prism's centre
             (version 1: measurements with known correspondence)

sonar options:
  --images                 also render the acoustic images (version 2):
                           images/<step>.png, polar, 8-bit dB, from the scene
                           (the prism on a floor, or in a tank) written to
                           truth/scene.ply; truth features are the prism's 8
                           vertices, measurements.csv the ones each image shows
  --range-bins N --beams N image size (default 512 x 128, the ARIS 3000)

options (each overrides the preset):
  --seed N                 random seed (default 1)
  --mesh PATH              survey a mesh file instead of the parametric hull
  --mesh-scale S           scale applied to the mesh on load (e.g. 59.4)
  --forward X,Y,Z          hull forward axis in the mesh (default 1,0,0)
  --up X,Y,Z               hull up axis in the mesh (default 0,0,1)
  --waterline W            waterline height along up (default: draft, or 60 % of the mesh height)
  --camera stereo|mono
  --camera-scale S         scale the cameras' pixel grid (1360x1024 at 1; 0.5: 680x512)
  --coverage bottom|full   bottom stretch, or the whole bottom and both sides
  --start M --end M        survey extent along the hull (m from the stern)
  --half-width M           bottom tracks within +-M of the centreline
  --standoff M             camera-to-hull distance (default 1.5)
  --track-spacing M        distance between lawnmower tracks
  --keyframe-spacing M     distance between keyframes along a track
  --objects none|demo|scattered   foreign structure
  --patches N              extra random fouling patches (with --objects scattered)
  --grow N --growth M --remove N --add N
                           the second survey of a pair (same --seed): the
                           first N patches grown by M (default 0.05), the
                           last N objects at least 0.08 m high removed,
                           N new patches
  --pixel-sigma PX --dvl-sigma M --feature-density PER_M2 --non-salient FRACTION
  --wrong-matches FRACTION (monocular)
  --servo-bias-deg D --model-pose-error-m M --model-pose-error-deg D
  --extrinsic-error-m M --extrinsic-error-deg D
  --write-landmarks        also write landmarks.csv (noisy initial positions)
  --shift X,Y              move the survey's frame: every position in g (nav.csv,
                           landmarks.csv, the model pose guess, truth/) X m east
                           and Y m north, as surveys in UTM coordinates arrive
                           (e.g. 400000,5000000); not with --images
  --images                 also render the camera images (bundle version 2)
  --image-dropout P        probability that an image is missing (dropped frame; default 0)
  --attenuation C          water attenuation, 1/m (default 0.3)
  --backscatter B          water backscatter, 1/(m sr) (default 0.0015)
  --gen-extras             also write DIR.gen/ (object meshes, wrong matches,
                           DVL drop-outs) for ../shared/tools/check-bundle.py
  --quiet                  no progress output
)";

Eigen::Vector3d ParseVector3(const std::string& name, const std::string& text) {
  std::stringstream ss(text);
  std::string item;
  Eigen::Vector3d v;
  int i = 0;
  while (std::getline(ss, item, ',')) {
    double x = 0;
    if (i >= 3 || !ParseFiniteDouble(item, x)) throw UsageError("--" + name + " expects X,Y,Z, got '" + text + "'");
    v[i++] = x;
  }
  if (i != 3) throw UsageError("--" + name + " expects X,Y,Z, got '" + text + "'");
  return v;
}

}  // namespace

int RunSimulate(const CommandArgs& argv) {
  Args a(argv, {"write-landmarks", "gen-extras", "quiet", "images"});
  if (a.Has("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  a.AllowOnly({"preset",
               "out",
               "seed",
               "mesh",
               "mesh-scale",
               "forward",
               "up",
               "waterline",
               "camera",
               "camera-scale",
               "coverage",
               "start",
               "end",
               "half-width",
               "standoff",
               "track-spacing",
               "keyframe-spacing",
               "objects",
               "patches",
               "grow",
               "growth",
               "remove",
               "add",
               "pixel-sigma",
               "dvl-sigma",
               "feature-density",
               "non-salient",
               "wrong-matches",
               "servo-bias-deg",
               "model-pose-error-m",
               "model-pose-error-deg",
               "extrinsic-error-m",
               "extrinsic-error-deg",
               "write-landmarks",
               "shift",
               "images",
               "image-dropout",
               "attenuation",
               "backscatter",
               "gen-extras",
               "quiet",
               "range-bins",
               "beams"});
  if (!a.positionals().empty()) throw UsageError("unexpected argument '" + a.positionals()[0] + "'");
  const std::string out = a.Get("out");
  if (out.empty()) throw UsageError("--out DIR is required");
  CheckOutputFolder(out);
  const std::string preset = a.Get("preset", "demo");
  if (preset.rfind("sonar-", 0) == 0 && a.Has("images")) {
    SonarImageSimulationOptions o = SonarImagePreset(preset.substr(6), static_cast<std::uint64_t>(a.GetInt("seed", 1)));
    o.format.range_bins = static_cast<int>(a.GetInt("range-bins", o.format.range_bins));
    o.format.beams = static_cast<int>(a.GetInt("beams", o.format.beams));
    ConsoleProgress progress(a.Has("quiet"));
    const SonarImageSimulation sim = SimulateSonarImages(o, &progress);
    WriteSonarImageSimulation(sim, out);
    progress.Finish();
    std::printf("wrote %s: %d steps, %zu images of %d x %d (range bins x beams), %zu measurements\n", out.c_str(),
                sim.sequence.num_steps(), sim.images.size(), o.format.range_bins, o.format.beams,
                sim.sequence.measurements.size());
    return kExitOk;
  }
  if (a.Has("range-bins") || a.Has("beams")) {
    throw UsageError("--range-bins and --beams need a sonar preset (sonar-prism, sonar-tank, sonar-above)");
  }
  if (preset.rfind("sonar-", 0) == 0) {
    const AcousticSequence seq = SimulateSonarPreset(preset.substr(6), static_cast<std::uint64_t>(a.GetInt("seed", 1)));
    WriteAcousticSequence(seq, out);
    std::printf("wrote %s: %d steps, %zu measurements\n", out.c_str(), seq.num_steps(), seq.measurements.size());
    return kExitOk;
  }
  SurveySimulationOptions o = SurveyPreset(preset);
  o.seed = static_cast<std::uint64_t>(a.GetInt("seed", 1));
  o.mesh_path = a.Get("mesh", "");
  o.mesh_scale = a.GetDouble("mesh-scale", o.mesh_scale);
  if (a.Has("forward")) o.forward = ParseVector3("forward", a.Get("forward"));
  if (a.Has("up")) o.up = ParseVector3("up", a.Get("up"));
  o.waterline = a.GetDouble("waterline", o.waterline);
  if (a.Has("camera")) {
    const std::string c = a.Get("camera");
    if (c != "stereo" && c != "mono") throw UsageError("--camera expects stereo or mono");
    o.camera = c == "stereo" ? CameraType::kStereo : CameraType::kMono;
  }
  o.camera_scale = a.GetDouble("camera-scale", o.camera_scale);
  if (a.Has("coverage")) {
    const std::string c = a.Get("coverage");
    if (c != "bottom" && c != "full") throw UsageError("--coverage expects bottom or full");
    o.plan.coverage = c == "full" ? SurveyCoverage::kFullHull : SurveyCoverage::kBottomPatch;
  }
  o.plan.start = a.GetDouble("start", o.plan.start);
  o.plan.end = a.GetDouble("end", o.plan.end);
  o.plan.half_width = a.GetDouble("half-width", o.plan.half_width);
  o.plan.standoff = a.GetDouble("standoff", o.plan.standoff);
  o.plan.track_spacing = a.GetDouble("track-spacing", o.plan.track_spacing);
  o.plan.keyframe_spacing = a.GetDouble("keyframe-spacing", o.plan.keyframe_spacing);
  if (a.Has("objects")) {
    const std::string s = a.Get("objects");
    if (s == "none")
      o.objects = ObjectSet::kNone;
    else if (s == "demo")
      o.objects = ObjectSet::kDemo;
    else if (s == "scattered")
      o.objects = ObjectSet::kScattered;
    else
      throw UsageError("--objects expects none, demo or scattered");
  }
  o.scattered_patches = static_cast<int>(a.GetInt("patches", o.scattered_patches));
  o.changes.grow = static_cast<int>(a.GetInt("grow", o.changes.grow));
  o.changes.growth = a.GetDouble("growth", o.changes.growth);
  o.changes.remove = static_cast<int>(a.GetInt("remove", o.changes.remove));
  o.changes.add = static_cast<int>(a.GetInt("add", o.changes.add));
  o.noise.pixel_sigma = a.GetDouble("pixel-sigma", o.noise.pixel_sigma);
  o.noise.dvl_range_sigma = a.GetDouble("dvl-sigma", o.noise.dvl_range_sigma);
  o.hull_feature_density = a.GetDouble("feature-density", o.hull_feature_density);
  o.non_salient_fraction = a.GetDouble("non-salient", o.non_salient_fraction);
  o.wrong_match_fraction = a.GetDouble("wrong-matches", o.wrong_match_fraction);
  o.servo_bias_deg = a.GetDouble("servo-bias-deg", o.servo_bias_deg);
  o.model_pose_error_m = a.GetDouble("model-pose-error-m", o.model_pose_error_m);
  o.model_pose_error_deg = a.GetDouble("model-pose-error-deg", o.model_pose_error_deg);
  o.extrinsic_error_m = a.GetDouble("extrinsic-error-m", o.extrinsic_error_m);
  o.extrinsic_error_deg = a.GetDouble("extrinsic-error-deg", o.extrinsic_error_deg);
  o.write_landmarks = a.Has("write-landmarks");
  if (a.Has("shift")) {
    const Eigen::Vector3d v = ParseVector3("shift", a.Get("shift") + ",0");
    o.shift = Eigen::Vector3d(v.x(), v.y(), 0.0);
  }
  o.images = a.Has("images");
  for (const char* name : {"image-dropout", "attenuation", "backscatter"}) {
    if (a.Has(name) && !o.images) throw UsageError(std::string("--") + name + " needs --images");
  }
  o.imaging.image_dropout = a.GetDouble("image-dropout", o.imaging.image_dropout);
  o.imaging.attenuation = a.GetDouble("attenuation", o.imaging.attenuation);
  o.imaging.backscatter = a.GetDouble("backscatter", o.imaging.backscatter);

  ConsoleProgress progress(a.Has("quiet"));
  const SimulatedSurvey s = SimulateSurvey(o, progress);
  WriteSimulatedSurvey(s, out, a.Has("gen-extras"), progress);
  progress.Finish();
  std::printf("wrote %s: %zu keyframes, %zu landmarks, %zu observations, %zu objects", out.c_str(), s.bundle.nav.size(),
              s.bundle.truth->landmarks.size(), s.bundle.features.size(), s.bundle.truth->objects.size());
  if (s.bundle.images) {
    std::printf(", %d images (%d dropped)", s.bundle.images->present(), s.bundle.images->dropped);
  }
  std::printf("\n");
  return kExitOk;
}

}  // namespace hull::cli
