#include "synthetic_results.h"

#include <cmath>
#include <unordered_map>

#include "base/progress.h"
#include "mapping/mapper.h"
#include "synthetic_survey.h"
#include "ui/session/survey_overlays.h"

namespace hull::ui::testing {

namespace {

AdjustmentRun MakeRun(SurfaceModel model) {
  const SyntheticSurvey& s = MakeSyntheticSurvey();
  const SurveyBundle& b = *s.bundle;
  auto r = std::make_shared<AdjustmentResult>();
  r->options.model = model;
  for (const TruePose& p : b.truth->poses) {
    r->keyframes.push_back(p.keyframe);
    r->poses.push_back(p.x_gv);
    r->servo.push_back(p.servo);
  }
  r->x_gM = r->x_gM_initial = b.truth->x_gM;
  std::unordered_map<std::int64_t, int> observations;
  for (const FeatureObservation& f : b.features) ++observations[f.landmark];
  // The bottom's outward normal in g.
  const Eigen::Vector3d out = Pose::FromVector(b.truth->x_gM).Rotate(-Eigen::Vector3d::UnitZ());
  for (const TrueLandmark& l : b.truth->landmarks) {
    LandmarkEstimate e;
    e.id = l.landmark;
    double d = l.deviation;
    if (model == SurfaceModel::kNaive) d += 0.015;
    if (model == SurfaceModel::kAllOnSurface) d *= 0.3;
    e.p = l.p + (d - l.deviation) * out;
    e.deviation = d;
    e.label = MaxMixtureLabel(d, 1.0, 0.02);
    e.observations = observations[l.landmark];
    r->landmarks.push_back(e);
  }
  int k = 0;
  for (const DvlRecord& d : b.dvl) {
    for (int beam = 0; beam < 4; ++beam) {
      DvlResidual res;
      res.keyframe = d.keyframe;
      res.beam = beam + 1;
      res.measured = d.range[beam];
      res.initial = -0.045 + 0.03 * std::sin(1.3 * k + beam) + 0.02 * std::cos(0.7 * k);
      res.final = 0.004 * std::sin(2.1 * k + 1.7 * beam);
      r->dvl.push_back(res);
    }
    ++k;
  }
  const int n = model == SurfaceModel::kAllOnSurface ? 14 : (model == SurfaceModel::kNaive ? 10 : 12);
  double on = 0;
  for (const LandmarkEstimate& e : r->landmarks) on += e.label;
  on /= static_cast<double>(r->landmarks.size());
  for (int i = 0; i <= n; ++i) {
    IterationRecord it;
    it.iteration = i;
    it.cost = 4e5 * std::exp(-0.7 * i) + (model == SurfaceModel::kNaive ? 1.5e4 : 2.2e4);
    it.seconds = 0.2 * i;
    it.fraction_on_surface = on - (on - 0.55) * std::exp(-0.6 * i);
    r->iterations.push_back(it);
  }
  r->seconds = model == SurfaceModel::kNaive ? 2.0 : (model == SurfaceModel::kAllOnSurface ? 3.0 : 2.45);
  r->solver_seconds = r->seconds - 0.1;
  r->initial_cost = r->iterations.front().cost;
  r->final_cost = r->iterations.back().cost;
  r->converged = true;
  AdjustmentRun run;
  run.key = SurfaceModelName(model);
  run.overlays = std::make_shared<const AdjustedOverlays>(ComputeAdjustedOverlays(b, *r));
  run.result = r;
  return run;
}

}  // namespace

std::shared_ptr<const AdjustmentRun> SyntheticRun(SurfaceModel model) {
  return std::make_shared<const AdjustmentRun>(MakeRun(model));
}

const Session::ModelRuns& SyntheticRuns() {
  static const Session::ModelRuns runs = {{SurfaceModel::kNaive, SyntheticRun(SurfaceModel::kNaive)},
                                          {SurfaceModel::kAllOnSurface, SyntheticRun(SurfaceModel::kAllOnSurface)},
                                          {SurfaceModel::kMaxMixture, SyntheticRun(SurfaceModel::kMaxMixture)}};
  return runs;
}

std::shared_ptr<const MappingRun> SyntheticMapping() {
  static const std::shared_ptr<const MappingRun> mapping = [] {
    const SyntheticSurvey& s = MakeSyntheticSurvey();
    // Made-up landmark sigmas (2 to 5 mm, varying by id) so that the fused
    // model carries per-vertex sigmas and the objects a height sigma.
    MappingInput input = MappingInputFromTruth(*s.bundle);
    for (MappingLandmark& l : input.landmarks) l.sigma_h = 0.002 + 0.0005 * static_cast<double>(l.id % 7);
    Mapper mapper(std::move(input), *s.mesh);
    NullProgress progress;
    auto run = std::make_shared<MappingRun>();
    auto result = std::make_shared<const MappingResult>(mapper.Run(MappingOptions(), progress));
    run->key = "synthetic";
    run->input = std::make_shared<const MappingInput>(mapper.input());
    run->overlays = std::make_shared<const MappingOverlays>(ComputeMappingOverlays(*result, *s.mesh));
    run->result = std::move(result);
    return run;
  }();
  return mapping;
}

void LookAtTheCylinder(SceneView& scene) {
  const auto& survey = MakeSyntheticSurvey();
  const Pose x_gM = PlacementPose(survey.bundle.get(), ModelPlacement::kTruth);
  const Eigen::Vector3d centre = x_gM * Eigen::Vector3d(2.0, 0.75, 0.0);
  CameraState c;
  c.focal_point = {centre.x(), centre.y(), centre.z()};
  c.position = {centre.x() + 0.8, centre.y() - 1.2, centre.z() + 2.6};
  c.view_up = {1, 0, 0};
  c.view_angle = 30;
  scene.SetCamera(c);
}

}  // namespace hull::ui::testing
