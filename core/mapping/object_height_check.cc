#include "mapping/object_height_check.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <set>

#include "base/error.h"

namespace hull {
namespace {

// Tangent frame of a true object (as the simulator's MakeObjectMesh builds it).
struct Frame {
  Eigen::Vector3d e1, e2, n;
  explicit Frame(const TrueObject& o) {
    n = o.normal.normalized();
    e1 = Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitX().dot(n) * n;
    if (e1.norm() < 1e-6) e1 = n.unitOrthogonal();
    e1.normalize();
    e2 = n.cross(e1);
  }
};

// The union of the objects' meshes (the true surface above the CAD) and
// which object each of its faces belongs to.
struct TrueSurface {
  TriangleMesh mesh;
  std::vector<int> object_of_face;
  std::unique_ptr<MeshIndex> index;
  explicit TrueSurface(const std::vector<TriangleMesh>& objects) {
    for (std::size_t i = 0; i < objects.size(); ++i) {
      mesh.Append(objects[i]);
      object_of_face.resize(mesh.num_faces(), static_cast<int>(i));
    }
    mesh.ComputeNormals();
    index = std::make_unique<MeshIndex>(mesh);
  }
  // The object whose top surface is the highest over p (the first face met
  // coming down along -n from above p, turned up), or -1; *top: that point.
  int TopAt(const Eigen::Vector3d& p, const Eigen::Vector3d& n, double reach, Eigen::Vector3d* top) const {
    const RayHit hit = index->Raycast(p + reach * n, -n, 2 * reach);
    if (!hit.hit) return -1;
    const auto face = static_cast<std::size_t>(hit.face);
    if (!(mesh.face_normals[face].dot(n) > 0)) return -1;
    if (top) *top = hit.point;
    return object_of_face[face];
  }
};

double NearestRank(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[std::min(v.size(), std::max<std::size_t>(rank, 1)) - 1];
}

}  // namespace

Pose GaugeFitToTruth(const SurveyBundle& bundle, const AdjustmentResult& adjustment) {
  if (!bundle.truth) {
    throw InputError({bundle.directory + "/truth", 0, 0, ""}, "the bundle has no truth to fit the gauge to");
  }
  std::map<std::int64_t, Eigen::Vector3d> truth;
  const Pose true_Mg = Pose::FromVector(bundle.truth->x_gM).Inverse();
  for (const auto& l : bundle.truth->landmarks) truth[l.landmark] = true_Mg * l.p;
  const Pose est_Mg = Pose::FromVector(adjustment.x_gM).Inverse();
  Eigen::Matrix3Xd src(3, static_cast<Eigen::Index>(adjustment.landmarks.size())), dst = src;
  Eigen::Index n = 0;
  for (const auto& l : adjustment.landmarks) {
    const auto it = truth.find(l.id);
    if (it == truth.end()) continue;
    src.col(n) = est_Mg * l.p;
    dst.col(n) = it->second;
    ++n;
  }
  if (n < 3) {
    throw InputError({bundle.directory + "/truth/landmarks.csv", 0, 0, "landmark"},
                     "fewer than 3 adjusted landmarks have a true position");
  }
  return Pose::FromMatrix(Eigen::umeyama(src.leftCols(n), dst.leftCols(n), false));
}

std::vector<ObjectHeightCheck> CheckObjectHeights(const TriangleMesh& model, const std::vector<DetectedObject>& objects,
                                                  const MappingInput& input, const Pose& model_to_true,
                                                  const std::vector<TrueObject>& truth,
                                                  const std::vector<TriangleMesh>& object_meshes, const MeshIndex& cad,
                                                  const std::vector<KeyframeShapes>* shapes) {
  if (object_meshes.size() != truth.size()) {
    throw std::invalid_argument("CheckObjectHeights: " + std::to_string(object_meshes.size()) + " object meshes for " +
                                std::to_string(truth.size()) + " objects");
  }
  const std::vector<double>* deviation = model.FindScalar("deviation");
  const std::vector<double>* fusions = model.FindScalar("fusions");
  if (!deviation || !fusions) throw std::invalid_argument("CheckObjectHeights: the model has no deviation/fusions");

  const TrueSurface surface(object_meshes);

  std::vector<Eigen::Vector3d> vertices(model.num_vertices());
  for (std::size_t v = 0; v < vertices.size(); ++v) vertices[v] = model_to_true * model.vertices[v];
  std::vector<int> object_of(model.num_vertices(), -1);
  for (std::size_t d = 0; d < objects.size(); ++d) {
    for (const int v : objects[d].vertices) object_of[static_cast<std::size_t>(v)] = static_cast<int>(d);
  }
  const Pose Mg = input.x_gM.Inverse();
  std::vector<Eigen::Vector3d> landmarks(input.landmarks.size());
  for (std::size_t l = 0; l < landmarks.size(); ++l) landmarks[l] = model_to_true * (Mg * input.landmarks[l].p_g);

  std::vector<int> shaped(input.landmarks.size(), 0);  // keyframes whose shapes hold the landmark
  if (shapes) {
    for (const auto& ks : *shapes) {
      for (const auto& sh : ks.shapes) {
        for (const int pi : sh.points)
          ++shaped[static_cast<std::size_t>(ks.points[static_cast<std::size_t>(pi)].landmark)];
      }
    }
  }
  std::vector<ObjectHeightCheck> out;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const TrueObject& o = truth[i];
    const Frame f(o);
    const double reach = std::max(1.0, 4 * o.Height());
    const double r = o.kind == ObjectKind::kBox ? 0.5 * std::hypot(o.size.x(), o.size.y()) : o.radius;
    ObjectHeightCheck c;
    c.id = o.id;
    c.kind = o.kind;
    c.height = o.Height();
    // The true surface's highest point where the object is the top (its
    // footprint less where a neighbour stands higher): a 5 mm grid over the
    // footprint's bounding disc.
    c.true_max = -std::numeric_limits<double>::infinity();
    const double step = 0.005;
    const int n = static_cast<int>(std::ceil(r / step));
    for (int a = -n; a <= n; ++a) {
      for (int b = -n; b <= n; ++b) {
        const Eigen::Vector3d p = o.center + a * step * f.e1 + b * step * f.e2;
        Eigen::Vector3d top;
        if ((p - o.center).norm() > r + 1e-9 || surface.TopAt(p, f.n, reach, &top) != static_cast<int>(i)) continue;
        c.true_max = std::max(c.true_max, cad.SignedDistance(top));
      }
    }
    if (!std::isfinite(c.true_max)) c.true_max = std::nan("");  // nowhere on top
    // The model's vertices over the footprint.
    std::vector<double> heights;
    std::set<std::string> detected;
    for (std::size_t v = 0; v < vertices.size(); ++v) {
      if ((vertices[v] - o.center).norm() > r + 4 * o.Height() + 0.05) continue;
      if (surface.TopAt(vertices[v], f.n, reach, nullptr) != static_cast<int>(i)) continue;
      heights.push_back((*deviation)[v]);
      if (c.model_max_vertex < 0 || (*deviation)[v] > (*deviation)[static_cast<std::size_t>(c.model_max_vertex)])
        c.model_max_vertex = static_cast<int>(v);
      c.fused_vertices += (*fusions)[v] > 0;
      if (object_of[v] >= 0) detected.insert(objects[static_cast<std::size_t>(object_of[v])].id);
    }
    c.model_vertices = static_cast<int>(heights.size());
    c.model_max = heights.empty() ? std::nan("") : *std::max_element(heights.begin(), heights.end());
    c.model_p95 = NearestRank(heights, 0.95);
    c.detected_as.assign(detected.begin(), detected.end());
    // The adjusted features over it.
    std::vector<double> feats;
    std::vector<std::pair<double, int>> over;
    c.shaped_max = std::nan("");
    for (std::size_t l = 0; l < landmarks.size(); ++l) {
      if ((landmarks[l] - o.center).norm() > r + 4 * o.Height() + 0.05) continue;
      if (surface.TopAt(landmarks[l], f.n, reach, nullptr) != static_cast<int>(i)) continue;
      feats.push_back(input.landmarks[l].deviation);
      over.emplace_back(input.landmarks[l].deviation, static_cast<int>(l));
      if (shaped[l] >= 2 && !(c.shaped_max >= input.landmarks[l].deviation))
        c.shaped_max = input.landmarks[l].deviation;
    }
    std::sort(feats.begin(), feats.end(), std::greater<>());
    std::sort(over.begin(), over.end(), std::greater<>());
    for (const auto& [d, l] : over) c.landmarks.push_back(l);
    c.features = static_cast<int>(feats.size());
    c.feature_max = feats.empty() ? std::nan("") : feats[0];
    c.feature_robust_max = feats.size() < 2 ? std::nan("") : feats[1];
    out.push_back(std::move(c));
  }
  return out;
}

FoundObjects CountFoundObjects(const std::vector<ObjectHeightCheck>& checks, const std::vector<DetectedObject>& objects,
                               double min_height) {
  FoundObjects f;
  std::set<std::string> on_truth;
  for (const ObjectHeightCheck& c : checks) {
    on_truth.insert(c.detected_as.begin(), c.detected_as.end());
    if (c.height < min_height) continue;
    ++f.required;
    if (c.detected_as.empty()) {
      f.missed.push_back(c.id);
    } else {
      ++f.found;
    }
  }
  for (const DetectedObject& d : objects) {
    if (!on_truth.count(d.id)) f.false_objects.push_back(d.id);
  }
  return f;
}

std::string FoundObjects::ToString() const {
  auto join = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s.empty() ? std::string("none") : s;
  };
  return "found " + std::to_string(found) + " of " + std::to_string(required) + " (missed: " + join(missed) +
         "); false objects: " + std::to_string(false_objects.size()) + " (" + join(false_objects) + ")\n";
}

std::string ObjectHeightTable(const std::vector<ObjectHeightCheck>& checks, double min_height, double tolerance) {
  std::string s =
      "| object | true height | true max in its region | model max | error | model p95 | features: highest, 2nd | "
      "in 2+ shapes, highest | vertices (fused) | detected as |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
  int considered = 0, within = 0, unmapped = 0, features_within = 0, robust_within = 0, robust_considered = 0;
  double worst = 0;
  char line[512];
  for (const auto& c : checks) {
    std::string det;
    for (const auto& d : c.detected_as) det += (det.empty() ? "" : ", ") + d;
    std::snprintf(
        line, sizeof line, "| %s | %.3f | %.3f | %.3f | %+.3f | %.3f | %d: %.3f, %.3f | %.3f | %d (%d) | %s |\n",
        c.id.c_str(), c.height, c.true_max, c.model_max, c.error(), c.model_p95, c.features, c.feature_max,
        c.feature_robust_max, c.shaped_max, c.model_vertices, c.fused_vertices, det.empty() ? "-" : det.c_str());
    s += line;
    if (c.height < min_height || !std::isfinite(c.true_max)) continue;
    ++considered;
    features_within += c.feature_max >= c.true_max - tolerance;
    if (!std::isfinite(c.model_max)) {
      ++unmapped;  // no model vertex in its region
      continue;
    }
    const double e = std::abs(c.error());
    within += e <= tolerance;
    if (std::isfinite(c.shaped_max)) {  // the highest feature two views' shapes hold
      ++robust_considered;
      robust_within += std::abs(c.model_max - c.shaped_max) <= tolerance;
    }
    worst = std::max(worst, e);
  }
  std::snprintf(line, sizeof line,
                "objects of at least %.2f m: %d of %d with the model max within %.3f m of the true max (worst %.3f m; "
                "%d with no model vertex in their region); the highest feature within %.3f m for %d of them\n",
                min_height, within, considered, tolerance, worst, unmapped, tolerance, features_within);
  s += line;
  std::snprintf(line, sizeof line,
                "the model max within %.3f m of the features' robust max (the highest in 2+ shapes) for %d of the %d "
                "with one\n",
                tolerance, robust_within, robust_considered);
  return s + line;
}

}  // namespace hull
