#include "adjust/evaluation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <unordered_map>

#include <Eigen/Eigenvalues>

#include "base/error.h"
#include "geometry/mesh_index.h"

namespace hull {
namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + static_cast<long>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

double RobustSpread(const std::vector<double>& v) {
  const double m = Median(v);
  std::vector<double> dev;
  dev.reserve(v.size());
  for (double x : v) dev.push_back(std::abs(x - m));
  return 1.4826 * Median(dev);
}

void MeanStd(const std::vector<double>& v, double& mean, double& sd) {
  mean = sd = 0;
  if (v.empty()) return;
  for (double x : v) mean += x;
  mean /= static_cast<double>(v.size());
  for (double x : v) sd += (x - mean) * (x - mean);
  sd = std::sqrt(sd / static_cast<double>(v.size()));
}

// Rigid motions (about centroid c: delta p = w x (p - c) + v) that keep every
// point on its surface to first order: the null space of sum J^T J with
// J_i = [((p_i - c) x n_i)^T, n_i^T]. Returns a 6 x k basis (w; v), unscaled.
Eigen::MatrixXd UnobservedMotions(const std::vector<Eigen::Vector3d>& p, const std::vector<Eigen::Vector3d>& n,
                                  const Eigen::Vector3d& c) {
  double L = 0;
  for (const auto& x : p) L = std::max(L, (x - c).norm());
  L = std::max(L, 1e-6);
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) {
    Eigen::Matrix<double, 6, 1> J;
    J.head<3>() = (p[i] - c).cross(n[i]) / L;
    J.tail<3>() = n[i];
    A += J * J.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> es(A);
  const double top = es.eigenvalues()[5];
  std::vector<int> null;
  for (int k = 0; k < 6; ++k) {
    if (es.eigenvalues()[k] < 1e-4 * top) null.push_back(k);
  }
  Eigen::MatrixXd N(6, static_cast<Eigen::Index>(null.size()));
  for (std::size_t j = 0; j < null.size(); ++j) {
    Eigen::Matrix<double, 6, 1> v = es.eigenvectors().col(null[j]);
    v.head<3>() /= L;  // back to radians
    N.col(static_cast<Eigen::Index>(j)) = v;
  }
  return N;
}

// Moves est toward truth along the motions N only (Gauss-Newton, exact rotation).
void AlignAlong(const Eigen::MatrixXd& N, const Eigen::Vector3d& c, std::vector<Eigen::Vector3d>& est,
                const std::vector<Eigen::Vector3d>& truth) {
  if (N.cols() == 0) return;
  for (int iter = 0; iter < 5; ++iter) {
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(N.cols(), N.cols());
    Eigen::VectorXd g = Eigen::VectorXd::Zero(N.cols());
    for (std::size_t i = 0; i < est.size(); ++i) {
      Eigen::Matrix<double, 3, 6> B;
      const Eigen::Vector3d d = est[i] - c;
      B.leftCols<3>() << 0, d.z(), -d.y(), -d.z(), 0, d.x(), d.y(), -d.x(), 0;  // w x d = -[d]x w
      B.rightCols<3>().setIdentity();
      const Eigen::MatrixXd BN = B * N;
      H += BN.transpose() * BN;
      g += BN.transpose() * (est[i] - truth[i]);
    }
    const Eigen::VectorXd a = -H.ldlt().solve(g);
    const Eigen::Matrix<double, 6, 1> xi = N * a;
    const double angle = xi.head<3>().norm();
    const Eigen::Matrix3d R =
        angle > 0 ? Eigen::AngleAxisd(angle, xi.head<3>() / angle).toRotationMatrix() : Eigen::Matrix3d::Identity();
    for (auto& e : est) e = R * (e - c) + c + xi.tail<3>();
    if (xi.norm() < 1e-12) break;
  }
}

// The adjusted landmarks that have a true one, both in M (each in its own
// estimate of M), and the true hull landmarks with the CAD's normal there.
struct MatchedLandmarks {
  std::vector<const LandmarkEstimate*> est;
  std::vector<const TrueLandmark*> truth;
  std::vector<Eigen::Vector3d> est_m, true_m, hull_p, hull_n;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // of true_m
};

MatchedLandmarks MatchToTruth(const SurveyTruth& t, const TriangleMesh& mesh, const AdjustmentResult& r) {
  const Pose est_Mg = Pose::FromVector(r.x_gM).Inverse();
  const Pose true_Mg = Pose::FromVector(t.x_gM).Inverse();
  std::unordered_map<std::int64_t, const TrueLandmark*> truth;
  for (const auto& l : t.landmarks) truth[l.landmark] = &l;
  const MeshIndex index(mesh);
  MatchedLandmarks m;
  for (const auto& l : r.landmarks) {
    auto it = truth.find(l.id);
    if (it == truth.end()) continue;
    m.est.push_back(&l);
    m.truth.push_back(it->second);
    m.est_m.push_back(est_Mg * l.p);
    m.true_m.push_back(true_Mg * it->second->p);
    m.centroid += m.true_m.back();
    if (it->second->object.empty()) {
      const ClosestPoint cp = index.Closest(m.true_m.back());
      m.hull_p.push_back(m.true_m.back());
      m.hull_n.push_back(mesh.face_normals[static_cast<std::size_t>(cp.face)]);
    }
  }
  if (!m.true_m.empty()) m.centroid /= static_cast<double>(m.true_m.size());
  return m;
}

// Landmark errors (gauge-aligned: est_m moved along the unobserved motions
// first), label agreement where the truth is clear (|deviation| < 2 cm or
// > 8 cm), the hull features' offset and spread, and per true object its
// landmarks' mean deviation against the true one.
void ScoreLandmarks(const MatchedLandmarks& m, const SurveyTruth& t, AdjustmentEvaluation& e) {
  double s_all = 0, s_hull = 0, s_obj = 0;
  std::size_t n_hull = 0, n_obj = 0, agree = 0;
  std::vector<double> hull_dev;
  std::map<std::string, std::pair<double, int>> per_object;
  std::map<std::string, double> per_object_truth;
  for (std::size_t i = 0; i < m.est.size(); ++i) {
    const LandmarkEstimate& l = *m.est[i];
    const TrueLandmark& tl = *m.truth[i];
    const double err2 = (m.est_m[i] - m.true_m[i]).squaredNorm();
    s_all += err2;
    ++e.landmarks;
    if (tl.object.empty()) {
      s_hull += err2;
      ++n_hull;
      hull_dev.push_back(l.deviation);
    } else {
      s_obj += err2;
      ++n_obj;
      auto& acc = per_object[tl.object];
      acc.first += l.deviation;
      acc.second += 1;
      per_object_truth[tl.object] += tl.deviation;
    }
    const double td = std::abs(tl.deviation);
    if (td < 0.02 || td > 0.08) {
      ++e.labels_checked;
      agree += (l.label == (td < 0.02 ? 1 : 0));
    }
  }
  if (e.landmarks) e.landmark_rmse = std::sqrt(s_all / static_cast<double>(e.landmarks));
  if (n_hull) e.landmark_rmse_hull = std::sqrt(s_hull / static_cast<double>(n_hull));
  if (n_obj) e.landmark_rmse_objects = std::sqrt(s_obj / static_cast<double>(n_obj));
  if (e.labels_checked) e.label_agreement = static_cast<double>(agree) / static_cast<double>(e.labels_checked);
  e.hull_feature_offset = Median(hull_dev);
  e.hull_feature_spread = RobustSpread(hull_dev);
  for (const auto& o : t.objects) {
    ObjectDeviation d;
    d.id = o.id;
    d.kind = ObjectKindName(o.kind);
    d.height = o.Height();
    auto it = per_object.find(o.id);
    if (it != per_object.end()) {
      d.landmarks = it->second.second;
      d.mean_deviation = it->second.first / it->second.second;
      d.true_mean_deviation = per_object_truth[o.id] / it->second.second;
    }
    e.objects.push_back(d);
  }
}

// The servo angles' mean error before (navigation) and after, the camera
// extrinsic's error before and after, and the DVL range residuals' mean,
// spread and robust spread before and after.
void ScoreSensors(const SurveyBundle& b, const SurveyTruth& t, const AdjustmentResult& r, AdjustmentEvaluation& e) {
  std::unordered_map<std::int64_t, const TruePose*> tp;
  for (const auto& p : t.poses) tp[p.keyframe] = &p;
  double sv0 = 0, sv1 = 0;
  std::size_t nv = 0;
  std::unordered_map<std::int64_t, double> nav_servo;
  for (const auto& n : b.nav) nav_servo[n.keyframe] = n.servo;
  for (std::size_t i = 0; i < r.keyframes.size(); ++i) {
    auto it = tp.find(r.keyframes[i]);
    if (it == tp.end()) continue;
    sv0 += std::abs(nav_servo[r.keyframes[i]] - it->second->servo);
    sv1 += std::abs(r.servo[i] - it->second->servo);
    ++nv;
  }
  if (nv) {
    e.servo_error_initial_deg = sv0 / static_cast<double>(nv) * 180 / M_PI;
    e.servo_error_final_deg = sv1 / static_cast<double>(nv) * 180 / M_PI;
  }
  const Pose ext_true = Pose::FromVector(t.x_s_cT);
  const Pose ext0 = Pose::FromVector(r.x_s_cT_initial), ext1 = Pose::FromVector(r.x_s_cT);
  e.extrinsic_error_initial_m = Pose::DistanceBetween(ext0, ext_true);
  e.extrinsic_error_final_m = Pose::DistanceBetween(ext1, ext_true);
  e.extrinsic_error_initial_deg = Pose::AngleBetween(ext0, ext_true) * 180 / M_PI;
  e.extrinsic_error_final_deg = Pose::AngleBetween(ext1, ext_true) * 180 / M_PI;
  std::vector<double> d0, d1;
  for (const auto& d : r.dvl) {
    if (std::isfinite(d.initial)) d0.push_back(d.initial);
    if (std::isfinite(d.final)) d1.push_back(d.final);
  }
  MeanStd(d0, e.dvl_mean_initial, e.dvl_std_initial);
  MeanStd(d1, e.dvl_mean_final, e.dvl_std_final);
  e.dvl_mad_initial = RobustSpread(d0);
  e.dvl_mad_final = RobustSpread(d1);
}

}  // namespace

const ObjectDeviation* AdjustmentEvaluation::Object(const std::string& id) const {
  for (const auto& o : objects) {
    if (o.id == id) return &o;
  }
  return nullptr;
}

AdjustmentEvaluation EvaluateAdjustment(const SurveyBundle& b, const TriangleMesh& mesh, const AdjustmentResult& r) {
  if (!b.truth) throw InputError({b.directory, 0, 0, "truth"}, "the survey has no truth/ to evaluate against");
  const SurveyTruth& t = *b.truth;
  AdjustmentEvaluation e;
  MatchedLandmarks m = MatchToTruth(t, mesh, r);
  // Raw errors, then gauge-aligned along the motions of M the surveyed hull
  // leaves unobserved.
  double raw = 0;
  for (std::size_t i = 0; i < m.est_m.size(); ++i) {
    raw += (m.est_m[i] - m.true_m[i]).squaredNorm();
    e.landmark_mean_error_raw += m.est_m[i] - m.true_m[i];
  }
  if (!m.est_m.empty()) {
    e.landmark_rmse_raw = std::sqrt(raw / static_cast<double>(m.est_m.size()));
    e.landmark_mean_error_raw /= static_cast<double>(m.est_m.size());
  }
  const Eigen::MatrixXd N = UnobservedMotions(m.hull_p, m.hull_n, m.centroid);
  e.unobservable_dof = static_cast<int>(N.cols());
  AlignAlong(N, m.centroid, m.est_m, m.true_m);
  ScoreLandmarks(m, t, e);
  ScoreSensors(b, t, r, e);
  return e;
}

std::string AdjustmentEvaluation::ToString() const {
  char buf[512];
  std::string s;
  // Figures over no landmark read as results ("RMSE 0.0000 m"): each is
  // printed only when it was measured on something.
  if (landmarks == 0) {
    s += "landmarks: none of the adjustment's landmarks has a true position: no landmark or label figures\n";
  } else {
    std::snprintf(buf, sizeof(buf),
                  "landmarks %zu: RMSE %.4f m gauge-aligned (%d unobserved DOF; raw %.4f m), hull %.4f, objects %.4f\n",
                  landmarks, landmark_rmse, unobservable_dof, landmark_rmse_raw, landmark_rmse_hull,
                  landmark_rmse_objects);
    s += buf;
    if (labels_checked > 0) {
      std::snprintf(buf, sizeof(buf), "labels: %.2f %% agree with truth (%zu checked)\n", 100 * label_agreement,
                    labels_checked);
    } else {
      std::snprintf(buf, sizeof(buf), "labels: none checked (no landmark clearly on or off the hull)\n");
    }
    s += buf;
    std::snprintf(buf, sizeof(buf), "features vs DVL: median deviation of hull features %+.4f m (spread %.4f m)\n",
                  hull_feature_offset, hull_feature_spread);
    s += buf;
  }
  std::snprintf(buf, sizeof(buf),
                "DVL residuals: std %.4f -> %.4f m, robust spread %.4f -> %.4f m, mean %+.4f -> %+.4f m\n"
                "servo error %.2f -> %.2f deg; extrinsic %.4f -> %.4f m, %.2f -> %.2f deg\n",
                dvl_std_initial, dvl_std_final, dvl_mad_initial, dvl_mad_final, dvl_mean_initial, dvl_mean_final,
                servo_error_initial_deg, servo_error_final_deg, extrinsic_error_initial_m, extrinsic_error_final_m,
                extrinsic_error_initial_deg, extrinsic_error_final_deg);
  s += buf;
  for (const auto& o : objects) {
    if (o.landmarks == 0) {
      std::snprintf(buf, sizeof(buf), "  %-10s %-8s height %.3f m: not observed (no landmark on it)\n", o.id.c_str(),
                    o.kind.c_str(), o.height);
    } else {
      std::snprintf(buf, sizeof(buf),
                    "  %-10s %-8s height %.3f m, mean deviation %.3f m (truth %.3f m) over %d landmarks\n",
                    o.id.c_str(), o.kind.c_str(), o.height, o.mean_deviation, o.true_mean_deviation, o.landmarks);
    }
    s += buf;
  }
  return s;
}

}  // namespace hull
