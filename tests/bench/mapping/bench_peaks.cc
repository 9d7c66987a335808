// Object heights and survey change end to end (issue 12, parts 1 and 4;
// docs/benchmarks.md, "Peaks per true object"):
//   bench_peaks [--preset demo|mono] [--pair] [--threads N] [--keep DIR [--reuse]] [--explain OBJECT]
//               [--fusion normal|peaks|mean] [--min-features N] [--tau M] [--grow-height M]
//               [--peak-fit | --no-peak-fit]
//
// The preset is simulated and written as a bundle (as `hullinspect-cli
// simulate` writes it), read back and run through the whole pipeline with
// its default options (as `hullinspect-cli run`: alignment, max-mixture
// adjustment, mapping). Then, per true object, the fused model's max height
// over the object's footprint against the true surface there
// (mapping/object_height_check.h), and the objects >= 6 cm found and the
// detected objects on no true object (false). --min-features N sets
// MappingOptions::object_min_features (0: the area test alone), --tau M the
// mapping's tau (default: MappingOptions', 0), --grow-height M the level
// Algorithm 1's hysteresis grows clusters down to
// (MappingOptions::shape_grow_height; a height >= tau turns it off). With --pair, the preset's second survey
// (2 patches grown by 5 cm, the last object removed, 2 new) too, and
// CompareSurveys (as `hullinspect-cli compare`) judged against the truth:
// every new, removed and >= 3 cm grown object reported, none false, the
// growth error. --keep DIR keeps the bundles and adjustments there; --reuse
// then maps the kept adjustments again (a change to the mapping in seconds).
// --fusion chooses the fusion as `hullinspect-cli map --fusion` does;
// --peak-fit / --no-peak-fit turn MappingOptions::peak_fit on or off (the
// fitted apexes over each true object are listed under the table).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <string>

#include <unistd.h>

#include "adjust/adjust_result.h"
#include "geometry/mesh_index.h"
#include "mapping/object_height_check.h"
#include "mapping/survey_compare.h"
#include "pipeline/pipeline.h"
#include "results/adjustment_files.h"
#include "simulate/survey_simulator.h"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct Survey {
  hull::SimulatedSurvey sim;
  hull::AdjustmentResult adjustment;
  hull::MappingResult mapping;
  hull::Pose to_true;  // the adjusted model frame to the true one
  std::vector<hull::ObjectHeightCheck> checks;
};

// Where the highest features over one true object's footprint went: per
// feature, its deviation, observations, and in how many of the keyframes
// that observed it it was below tau, DBSCAN noise, clustered but left out
// of the alpha shape, or a shape's vertex.
void Explain(const std::vector<hull::ObjectHeightCheck>& checks, const std::string& id, const hull::MappingInput& in,
             const hull::MappingResult& m) {
  for (const auto& c : checks) {
    if (c.id != id) continue;
    std::printf("\n%s: its %d highest features (of %d over the footprint)\n", id.c_str(),
                std::min(8, static_cast<int>(c.landmarks.size())), c.features);
    std::printf(
        "| landmark | deviation | keyframes observing | below tau | noise | clustered, not in a shape | in a shape "
        "|\n");
    std::printf("|---:|---:|---:|---:|---:|---:|---:|\n");
    for (std::size_t k = 0; k < c.landmarks.size() && k < 8; ++k) {
      const int l = c.landmarks[k];
      int seen = 0, below = 0, noise = 0, left = 0, shaped = 0;
      for (const auto& ks : m.keyframes) {
        for (std::size_t pi = 0; pi < ks.points.size(); ++pi) {
          const hull::ShapePoint& p = ks.points[pi];
          if (p.landmark != l) continue;
          ++seen;
          if (p.cluster == hull::ShapePoint::kBelowTau) {
            ++below;
          } else if (p.cluster == hull::ShapePoint::kNoise) {
            ++noise;
          } else {
            bool in_shape = false;
            for (const auto& sh : ks.shapes) {
              for (const int q : sh.points) in_shape = in_shape || q == static_cast<int>(pi);
            }
            ++(in_shape ? shaped : left);
          }
        }
      }
      std::printf("| %lld | %.3f | %d | %d | %d | %d | %d |\n",
                  static_cast<long long>(in.landmarks[static_cast<std::size_t>(l)].id),
                  in.landmarks[static_cast<std::size_t>(l)].deviation, seen, below, noise, left, shaped);
      // The nearest feature of each keyframe's points on the image plane (x, y).
      for (const auto& ks : m.keyframes) {
        for (const auto& p : ks.points) {
          if (p.landmark != l || p.cluster != hull::ShapePoint::kNoise) continue;
          double best = 1e9, best_d = 0;
          int best_cluster = 0;
          for (const auto& q : ks.points) {
            if (q.landmark == l || q.cluster == hull::ShapePoint::kBelowTau) continue;
            const double e = (q.p_c.head<2>() - p.p_c.head<2>()).norm();
            if (e < best) {
              best = e;
              best_d = q.deviation;
              best_cluster = q.cluster;
            }
          }
          std::printf(
              "|   keyframe %lld: noise; nearest feature on the image plane %.3f m away, deviation %.3f, cluster %d "
              "|\n",
              static_cast<long long>(ks.id), best, best_d, best_cluster);
        }
      }
    }
  }
}

// dir/bundle: the simulated bundle; dir/adjustment: its adjustment. With
// `reuse` and both there, the adjustment is read back and only the mapping
// runs (as `hullinspect-cli map` would on it).
Survey RunOne(const std::string& name, const hull::SurveySimulationOptions& so, const fs::path& dir, int threads,
              bool reuse, const std::string& explain, const hull::MappingOptions& mapping) {
  hull::NullProgress p;
  Survey s;
  s.sim = hull::SimulateSurvey(so, p);
  const std::string bundle = (dir / "bundle").string(), adjustment = (dir / "adjustment").string();
  reuse = reuse && fs::exists(adjustment) && fs::exists(bundle);
  if (!reuse) hull::WriteSimulatedSurvey(s.sim, bundle);
  const hull::PipelineInputs in = hull::LoadPipelineInputs(bundle);
  hull::PipelineOptions o;
  o.adjustment.num_threads = threads;
  o.mapping = mapping;
  o.mapping.num_threads = threads;
  const auto t = Clock::now();
  if (reuse) {
    s.adjustment = hull::ReadAdjustmentResult(adjustment);
    s.mapping = hull::RunMappingStep(in, s.adjustment, o.mapping, p);
  } else {
    hull::PipelineResult r = hull::RunPipeline(in, o, p);
    s.adjustment = std::move(r.adjustment);
    s.mapping = std::move(*r.mapping);
    hull::WriteAdjustmentResult(s.adjustment, adjustment);
  }
  s.to_true = hull::GaugeFitToTruth(in.bundle, s.adjustment);
  const hull::MappingResult& m = s.mapping;
  std::printf("\n## %s: %s %.1f s wall, %zu objects detected; adjusted M vs the true M: %.3f m, %.2f deg\n\n",
              name.c_str(), reuse ? "mapping (adjustment reused)" : "pipeline", Since(t), m.objects.size(),
              s.to_true.translation().norm(), hull::Pose::AngleBetween(s.to_true, hull::Pose()) * 180 / M_PI);
  const hull::MeshIndex cad(s.sim.cad);
  const hull::MappingInput in_map = hull::MappingInputFromAdjustment(s.adjustment, in.bundle);
  s.checks = hull::CheckObjectHeights(m.model, m.objects, in_map, s.to_true, s.sim.bundle.truth->objects,
                                      s.sim.object_meshes, cad, &m.keyframes);
  std::printf("%s", hull::ObjectHeightTable(s.checks, 0.06, 0.01).c_str());
  std::printf("objects of at least 0.06 m: %s", hull::CountFoundObjects(s.checks, m.objects, 0.06).ToString().c_str());
  if (!m.peaks.empty()) {
    // The peak fit's candidates over each true object.
    std::printf(
        "\n| object | top feature | apex (all features) | apex (lowest leave-one-out) | features | keyframes | rms "
        "| outcome |\n|---|---:|---:|---:|---:|---:|---:|---|\n");
    for (const auto& c : s.checks) {
      for (const auto& pk : m.peaks) {
        if (std::find(c.landmarks.begin(), c.landmarks.end(), pk.landmark) == c.landmarks.end()) continue;
        std::printf("| %s | %.3f | %.3f | %.3f | %d | %d | %.4f | %s |\n", c.id.c_str(), pk.top, pk.full_height,
                    pk.height, pk.features, pk.keyframes, pk.rms,
                    pk.accepted ? pk.placement.c_str() : pk.reason.c_str());
      }
    }
  }
  if (!explain.empty()) Explain(s.checks, explain, in_map, m);
  return s;
}

// The true object (of `truth`, in the true M) whose footprint disc lies
// nearest to p; its distance (0 inside).
const hull::TrueObject* NearestTrue(const std::vector<hull::TrueObject>& truth, const Eigen::Vector3d& p, double* d) {
  const hull::TrueObject* best = nullptr;
  *d = std::numeric_limits<double>::infinity();
  for (const auto& o : truth) {
    const double r = o.kind == hull::ObjectKind::kBox ? 0.5 * std::hypot(o.size.x(), o.size.y()) : o.radius;
    const double e = std::max(0.0, (p - o.center).norm() - r);
    if (e < *d) {
      *d = e;
      best = &o;
    }
  }
  return best;
}

void ComparePair(const Survey& a, const Survey& b) {
  const auto t = Clock::now();
  const hull::MappingResult &ma = a.mapping, &mb = b.mapping;
  const hull::SurveyComparison c =
      hull::CompareSurveys(a.sim.cad, ma.model, ma.objects, mb.model, mb.objects, hull::SurveyCompareOptions{});
  std::printf(
      "\n## compare A B: %.2f s; B registered to A by %d objects' tops in common (%d without, residual %.3f m); "
      "heights "
      "read within %.3f m of each peak\n\n",
      Since(t), c.registration.inliers, c.registration.identity_inliers, c.registration.rms, c.reach);
  std::map<std::string, const hull::TrueObject*> ta, tb;
  for (const auto& o : a.sim.bundle.truth->objects) ta[o.id] = &o;
  for (const auto& o : b.sim.bundle.truth->objects) tb[o.id] = &o;
  // What each reported row stands for in the truth: the true object nearest
  // its centroid (B's centroid where B has the object, else A's), in the
  // survey's own truth.
  struct Row {
    const hull::ObjectChange* c;
    const hull::TrueObject* at;
    double distance;
    std::string truth_kind;  // new / removed / grown / shrunk / unchanged
    double true_change;
  };
  std::vector<Row> rows;
  std::printf("| change | A | B | height A | height B | change | nearest true object | distance | true change |\n");
  std::printf("|---|---|---|---:|---:|---:|---|---:|---|\n");
  for (const auto& x : c.objects) {
    Row r{&x, nullptr, 0, "", 0};
    const bool in_b = !x.id_b.empty();
    const Eigen::Vector3d p = (in_b ? b.to_true : a.to_true) * x.centroid;
    r.at = NearestTrue(in_b ? b.sim.bundle.truth->objects : a.sim.bundle.truth->objects, p, &r.distance);
    const std::string& id = r.at->id;
    if (in_b && !ta.count(id)) {
      r.truth_kind = "new";
      r.true_change = r.at->Height();
    } else if (!in_b && !tb.count(id)) {
      r.truth_kind = "removed";
      r.true_change = -r.at->Height();
    } else {
      r.true_change = tb.at(id)->Height() - ta.at(id)->Height();
      r.truth_kind = r.true_change >= 0.03 ? "grown" : r.true_change <= -0.03 ? "shrunk" : "unchanged";
    }
    std::printf("| %s | %s | %s | %.3f | %.3f | %+.3f | %s | %.2f | %s %+.3f |\n", hull::ObjectChangeKindName(x.kind),
                x.id_a.empty() ? "-" : x.id_a.c_str(), x.id_b.empty() ? "-" : x.id_b.c_str(), x.height_a, x.height_b,
                x.change, id.c_str(), r.distance, r.truth_kind.c_str(), r.true_change);
    rows.push_back(r);
  }
  // Every true change reported (a row of its kind within 10 cm of it, or
  // whose detected object covers it: two touching lumps may be one detected
  // object), and every reported change true.
  auto covers = [](const Survey& s, const std::string& true_id, const std::string& detected) {
    for (const auto& k : s.checks) {
      if (k.id != true_id) continue;
      for (const auto& d : k.detected_as) {
        if (!detected.empty() && d == detected) return true;
      }
    }
    return false;
  };
  int expected = 0, reported = 0, false_changes = 0;
  double worst_growth = 0;
  auto check = [&](const std::string& kind, const hull::TrueObject& o, double true_change) {
    ++expected;
    const Row* hit = nullptr;
    for (const auto& r : rows) {
      if (hull::ObjectChangeKindName(r.c->kind) != kind) continue;
      const bool near = r.at->id == o.id && r.distance <= 0.10;
      const bool covered = kind == "removed" ? covers(a, o.id, r.c->id_a) : covers(b, o.id, r.c->id_b);
      if (near || (covered && !hit)) hit = &r;
    }
    std::printf("true %-7s %-9s %.3f m: %s", kind.c_str(), o.id.c_str(), true_change,
                hit ? "reported" : "NOT reported");
    if (hit && kind == "grown") {
      const double e = hit->c->change - true_change;
      worst_growth = std::max(worst_growth, std::abs(e));
      std::printf(" (measured %+.3f, error %+.3f)", hit->c->change, e);
    }
    std::printf("\n");
    reported += hit != nullptr;
  };
  for (const auto& [id, o] : tb) {
    if (!ta.count(id)) check("new", *o, o->Height());
  }
  for (const auto& [id, o] : ta) {
    if (!tb.count(id)) {
      check("removed", *o, -o->Height());
    } else if (tb.at(id)->Height() - o->Height() >= 0.03) {
      check("grown", *tb.at(id), tb.at(id)->Height() - o->Height());
    }
  }
  for (const auto& r : rows) {
    if (r.c->kind == hull::ObjectChangeKind::kUnchanged) continue;
    if (r.distance > 0.10 || hull::ObjectChangeKindName(r.c->kind) != r.truth_kind) ++false_changes;
  }
  std::printf("true changes reported: %d of %d; false changes: %d; worst growth error %.3f m\n", reported, expected,
              false_changes, worst_growth);
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 0, min_features = -1;
  double tau = -1, grow_height = -1;
  bool pair = false, reuse = false;
  int peak_fit = -1;  // -1: MappingOptions' default
  std::string explain;
  std::string preset = "demo", keep, fusion = "normal";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) {
      threads = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--preset") && i + 1 < argc) {
      preset = argv[++i];
    } else if (!std::strcmp(argv[i], "--keep") && i + 1 < argc) {
      keep = argv[++i];
    } else if (!std::strcmp(argv[i], "--explain") && i + 1 < argc) {
      explain = argv[++i];
    } else if (!std::strcmp(argv[i], "--min-features") && i + 1 < argc) {
      min_features = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--grow-height") && i + 1 < argc) {
      grow_height = std::atof(argv[++i]);
    } else if (!std::strcmp(argv[i], "--tau") && i + 1 < argc) {
      tau = std::atof(argv[++i]);
    } else if (!std::strcmp(argv[i], "--fusion") && i + 1 < argc &&
               (!std::strcmp(argv[i + 1], "normal") || !std::strcmp(argv[i + 1], "peaks") ||
                !std::strcmp(argv[i + 1], "mean"))) {
      fusion = argv[++i];
    } else if (!std::strcmp(argv[i], "--peak-fit")) {
      peak_fit = 1;
    } else if (!std::strcmp(argv[i], "--no-peak-fit")) {
      peak_fit = 0;
    } else if (!std::strcmp(argv[i], "--reuse")) {
      reuse = true;
    } else if (!std::strcmp(argv[i], "--pair")) {
      pair = true;
    } else {
      std::fprintf(
          stderr,
          "usage: bench_peaks [--preset demo|mono] [--pair] [--threads N] [--keep DIR [--reuse]] [--explain OBJECT] "
          "[--fusion normal|peaks|mean] [--min-features N] [--tau M] [--grow-height M] [--peak-fit | --no-peak-fit]\n");
      return 2;
    }
  }
  const fs::path dir =
      keep.empty() ? fs::temp_directory_path() / ("bench_peaks-" + std::to_string(::getpid())) : fs::path(keep);
  fs::create_directories(dir);
  hull::MappingOptions mapping;
  mapping.fusion_keep_peaks = fusion != "mean";
  mapping.fusion_along_normal = fusion == "normal";
  if (min_features >= 0) mapping.object_min_features = min_features;
  if (tau >= 0) mapping.tau = tau;
  if (grow_height >= 0) mapping.shape_grow_height = grow_height;
  if (peak_fit >= 0) mapping.peak_fit = peak_fit == 1;
  const hull::SurveySimulationOptions oa = hull::SurveyPreset(preset);
  const Survey a = RunOne(preset + " (A)", oa, dir / "a", threads, reuse, explain, mapping);
  if (pair) {
    hull::SurveySimulationOptions ob = oa;
    ob.changes.grow = 2;
    ob.changes.remove = 1;
    ob.changes.add = 2;
    const Survey b =
        RunOne(preset + " (B: --grow 2 --remove 1 --add 2)", ob, dir / "b", threads, reuse, explain, mapping);
    ComparePair(a, b);
  }
  if (keep.empty()) fs::remove_all(dir);
  return 0;
}
