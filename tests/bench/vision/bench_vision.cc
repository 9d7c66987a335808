// The visual front end at the survey's image size (1360x1024 stereo pairs of
// a textured cylinder rendered in code): SIFT per image, stereo matching per
// pair, temporal matching with RANSAC per keyframe pair, tracks, and the
// whole job per stereo keyframe (goal: >= 1 stereo keyframe/s on 2 cores).
//   bench_vision [keyframes=6] [threads=2]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>

#include "support/bench_clock.h"
#include "support/test_files.h"
#include "unit/vision/vision_scene.h"
#include "vision/feature_detection.h"
#include "vision/front_end.h"
#include "vision/stereo_matching.h"
#include "vision/temporal_matching.h"

namespace {
double Now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
// CPU time (s) of this thread and of the process: comparable on a loaded machine.
const auto ThreadCpu = hull::bench::ThreadCpuSeconds;
const auto ProcessCpu = hull::bench::CpuSeconds;
}  // namespace

int main(int argc, char** argv) {
  using namespace hull;
  const int keyframes = argc > 1 ? std::atoi(argv[1]) : 6;
  const int threads = argc > 2 ? std::atoi(argv[2]) : 2;
  testing::VisionScene s = testing::MakeVisionScene(true, true, keyframes, 0.2);
  CameraRig& rig = s.manifest.camera;
  rig.width = 1360;
  rig.height = 1024;
  rig.top = rig.bottom = PinholeIntrinsics{1150, 1150, 679.5, 511.5};
  const testing::ScratchDir dir("bench_vision");
  double t = Now();
  testing::WriteSceneBundle(s, dir.path());
  std::printf("rendered and wrote %d stereo keyframes of %dx%d in %.1f s\n", keyframes, rig.width, rig.height,
              Now() - t);
  const SurveyBundle bundle = ReadSurveyBundle(dir.path());
  FrontEndOptions o;
  o.threads = threads;

  // Stages on one thread.
  const cv::Mat top0 = s.Render(0), bottom0 = s.Render(0, true), top1 = s.Render(1), bottom1 = s.Render(1, true);
  const int reps = 3;
  t = ThreadCpu();
  ImageFeatures ft, fb;
  for (int i = 0; i < reps; ++i) ft = DetectFeatures(top0, o.detection);
  const double detect = (ThreadCpu() - t) / reps;
  fb = DetectFeatures(bottom0, o.detection);
  t = ThreadCpu();
  std::vector<StereoMatch> sm;
  for (int i = 0; i < reps; ++i) sm = MatchStereo(ft, fb, rig, o.stereo);
  const double stereo = (ThreadCpu() - t) / reps;
  KeyframeView a, b;
  a.x_g_cT = CameraPoseFromNav(s.manifest, s.nav[0]);
  a.top = ft;
  a.stereo = sm;
  b.x_g_cT = CameraPoseFromNav(s.manifest, s.nav[1]);
  b.top = DetectFeatures(top1, o.detection);
  b.stereo = MatchStereo(b.top, DetectFeatures(bottom1, o.detection), rig, o.stereo);
  t = ThreadCpu();
  PairMatches pm;
  for (int i = 0; i < reps; ++i) pm = MatchKeyframes(a, b, rig, o.temporal);
  const double temporal = (ThreadCpu() - t) / reps;
  std::printf(
      "one thread, CPU time: SIFT+CLAHE %.3f s/image (%zu features, %.0f features/s), stereo matching %.3f s/pair "
      "(%zu matches), temporal matching+RANSAC %.3f s/keyframe pair (%d putative, %d inliers)\n",
      detect, ft.size(), ft.size() / detect, stereo, sm.size(), temporal, pm.putative, pm.inliers);

  // The whole job (reading PNGs, every stage, tracks).
  NullProgress progress;
  t = Now();
  const double cpu0 = ProcessCpu();
  const FrontEndResult r = RunFrontEnd(bundle, o, progress);
  const double total = Now() - t, cpu = ProcessCpu() - cpu0;
  std::printf(
      "front end, %d threads: %d stereo keyframes in %.2f s = %.2f keyframes/s (%.3f s per stereo pair, "
      "%.0f features/s); %d landmarks, %zu observations\n",
      threads, keyframes, total, keyframes / total, total / keyframes,
      2.0 * keyframes * static_cast<double>(ft.size()) / total, r.landmarks, r.features.size());
  std::printf("  CPU time %.2f s = %.2f CPU-s per stereo keyframe, i.e. %.2f keyframes/s on %d idle cores\n", cpu,
              cpu / keyframes, threads * keyframes / cpu, threads);
  return 0;
}
