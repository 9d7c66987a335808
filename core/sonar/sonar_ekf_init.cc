// The sonar EKF's feature initialisation: the paper's (elevation 0) and the
// delayed elevation hypotheses with their stochastic clones (see sonar_ekf.h).
#include <ceres/jet.h>

#include <algorithm>
#include <cmath>

#include "sonar/acoustic_camera.h"
#include "sonar/sonar_ekf.h"

namespace hull {
namespace {

// A feature about to enter the state: its mean, the Jacobian of the inverse
// model with respect to the pose block at pose_offset (the current pose or an
// anchor clone) and the covariance contributed by the measurement and the
// elevation prior (J_polar diag(.) J_polar^T).
struct NewFeature {
  std::int64_t id = 0;
  std::int64_t first_step = 0;
  int observations = 1;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, 6> J_pose = Eigen::Matrix<double, 3, 6>::Zero();
  int pose_offset = 0;
  Eigen::Matrix3d polar_cov = Eigen::Matrix3d::Zero();
};

// The blocks that append new features in one resize: means b,
// cross-covariances C = J P(pose block, :) and B_ij = J_i P(a_i, a_j) J_j^T.
struct FeatureBlocks {
  Eigen::VectorXd b;
  Eigen::MatrixXd C, B;
};
FeatureBlocks MakeFeatureBlocks(const std::vector<NewFeature>& nf, const Eigen::MatrixXd& P) {
  FeatureBlocks out;
  Eigen::VectorXd& b = out.b;
  Eigen::MatrixXd &C = out.C, &B = out.B;
  const Eigen::Index n = 3 * static_cast<Eigen::Index>(nf.size()), N = P.rows();
  b.resize(n);
  C.resize(n, N);
  B.resize(n, n);
  for (std::size_t i = 0; i < nf.size(); ++i) {
    const auto r = 3 * static_cast<Eigen::Index>(i);
    b.segment<3>(r) = nf[i].mean;
    C.middleRows<3>(r).noalias() = nf[i].J_pose * P.middleRows<6>(nf[i].pose_offset);
  }
  for (std::size_t i = 0; i < nf.size(); ++i) {
    for (std::size_t j = 0; j <= i; ++j) {
      const auto ri = 3 * static_cast<Eigen::Index>(i), rj = 3 * static_cast<Eigen::Index>(j);
      Eigen::Matrix3d Bij = C.block<3, 6>(ri, nf[j].pose_offset) * nf[j].J_pose.transpose();
      if (i == j) Bij += nf[i].polar_cov;
      B.block<3, 3>(ri, rj) = Bij;
      B.block<3, 3>(rj, ri) = Bij.transpose();
    }
  }
  return out;
}

}  // namespace

void SonarEkf::InitialisePaper(const std::vector<const SonarMeasurement*>& fresh) {
  if (fresh.empty()) return;
  const double sigma_phi = options_.paper_elevation_sigma_fraction * sensor_.elevation_fov;
  std::vector<NewFeature> nf;
  for (const SonarMeasurement* m : fresh) {
    const Eigen::Vector2d noise = NoiseOf(*m);
    const Eigen::Vector3d var(noise[0] * noise[0], noise[1] * noise[1], sigma_phi * sigma_phi);
    NewFeature f;
    f.id = m->feature;
    f.first_step = step_;
    Eigen::Matrix3d J_polar;
    f.mean = SonarBackProjectJacobians(x_.head<6>(), m->range, m->azimuth, 0.0, &f.J_pose, &J_polar);
    f.pose_offset = 0;
    f.polar_cov = J_polar * var.asDiagonal() * J_polar.transpose();
    nf.push_back(f);
  }
  const FeatureBlocks blocks = MakeFeatureBlocks(nf, P_);
  const int base = Append(blocks.b, blocks.C, blocks.B);
  for (std::size_t i = 0; i < nf.size(); ++i) {
    features_[nf[i].id] = FeatureSlot{base + 3 * static_cast<int>(i), nf[i].observations, nf[i].first_step};
  }
}

int SonarEkf::CloneOffset(std::int64_t step) const {
  for (const Clone& c : clones_) {
    if (c.step == step) return c.offset;
  }
  return -1;
}

void SonarEkf::EnsureClone() {
  if (!clones_.empty() && clones_.back().step == step_) return;
  // Stochastic clone of the current pose: identical mean, fully correlated.
  const Eigen::VectorXd b = x_.head<6>();
  const Eigen::MatrixXd C = P_.topRows<6>();
  const Eigen::MatrixXd B = P_.topLeftCorner<6, 6>();
  const int offset = Append(b, C, B);
  clones_.push_back(Clone{step_, offset, 0});
}

std::vector<SonarEkf::HypothesisPrediction> SonarEkf::HypothesisPredictions(const Pending& pd) const {
  using Jet = ceres::Jet<double, 15>;
  const View& anchor = pd.views.front();
  const int a = CloneOffset(anchor.step);
  // Joint covariance of (current pose, anchor clone).
  Eigen::Matrix<double, 12, 12> Sigma;
  Sigma.topLeftCorner<6, 6>() = P_.topLeftCorner<6, 6>();
  Sigma.topRightCorner<6, 6>() = P_.block<6, 6>(0, a);
  Sigma.bottomLeftCorner<6, 6>() = P_.block<6, 6>(a, 0);
  Sigma.bottomRightCorner<6, 6>() = P_.block<6, 6>(a, a);
  const double sigma_h = Spacing() / 2;
  const Eigen::Vector3d polar_var(anchor.sigma[0] * anchor.sigma[0], anchor.sigma[1] * anchor.sigma[1],
                                  sigma_h * sigma_h);
  Eigen::Matrix<Jet, 6, 1> xt, xa;
  for (int i = 0; i < 6; ++i) {
    xt[i] = Jet(x_[i], i);
    xa[i] = Jet(x_[a + i], 6 + i);
  }
  const Jet r0(anchor.range, 12), t0(anchor.azimuth, 13);
  double total = 0;
  for (double l : pd.log_weight) total += std::exp(l);
  std::vector<HypothesisPrediction> out;
  for (std::size_t h = 0; h < pd.cell.size(); ++h) {
    // Predicted view of hypothesis h: h(x_t, g^-1(x_a, r0, theta0, phi_h)),
    // linearised in both poses, the first view's noise and the hypothesis' width.
    const Eigen::Matrix<Jet, 3, 1> p = SonarBackProject<Jet>(xa, r0, t0, Jet(CellElevation(pd.cell[h]), 14));
    const Eigen::Matrix<Jet, 2, 1> z = SonarMeasure<Jet>(xt, p);
    Eigen::Matrix<double, 2, 12> Jx;
    Eigen::Matrix<double, 2, 3> Jp;
    for (int r = 0; r < 2; ++r) {
      Jx.row(r) = z[r].v.head<12>().transpose();
      Jp.row(r) = z[r].v.tail<3>().transpose();
    }
    HypothesisPrediction hp;
    hp.z = Eigen::Vector2d(z[0].a, z[1].a);
    hp.S = Jx * Sigma * Jx.transpose() + Jp * polar_var.asDiagonal() * Jp.transpose();
    hp.weight = std::exp(pd.log_weight[h]) / total;
    out.push_back(hp);
  }
  return out;
}

void SonarEkf::WeighPending(Pending& pd, const SonarMeasurement& m) const {
  const std::vector<HypothesisPrediction> predictions = HypothesisPredictions(pd);
  const Eigen::Vector2d noise = NoiseOf(m);
  for (std::size_t h = 0; h < pd.cell.size(); ++h) {
    Eigen::Matrix2d S = predictions[h].S;
    S(0, 0) += noise[0] * noise[0];
    S(1, 1) += noise[1] * noise[1];
    const Eigen::Vector2d nu(m.range - predictions[h].z[0], WrapAngle(m.azimuth - predictions[h].z[1]));
    pd.log_weight[h] += -0.5 * nu.dot(S.ldlt().solve(nu)) - 0.5 * std::log(S.determinant());
    if (!std::isfinite(pd.log_weight[h])) {
      throw SonarNumericalError(
          step_, "the weight of an elevation hypothesis of feature " + std::to_string(pd.id) + " is not finite");
    }
  }
  // Normalise (best = 0) and prune.
  const double best = *std::max_element(pd.log_weight.begin(), pd.log_weight.end());
  const double floor = options_.prune_ratio > 0 ? std::log(options_.prune_ratio) : -INFINITY;
  std::vector<int> cell;
  std::vector<double> lw;
  for (std::size_t h = 0; h < pd.cell.size(); ++h) {
    const double l = pd.log_weight[h] - best;
    if (l >= floor) {
      cell.push_back(pd.cell[h]);
      lw.push_back(l);
    }
  }
  pd.cell = std::move(cell);
  pd.log_weight = std::move(lw);
}

SonarEkf::Collapse SonarEkf::CollapseOf(const Pending& pd) const {
  double total = 0;
  std::size_t best = 0;
  for (std::size_t h = 0; h < pd.cell.size(); ++h) {
    total += std::exp(pd.log_weight[h]);
    if (pd.log_weight[h] > pd.log_weight[best]) best = h;
  }
  double mass = 0, mean = 0;
  for (std::size_t h = 0; h < pd.cell.size(); ++h) {
    if (std::abs(pd.cell[h] - pd.cell[best]) > 1) continue;
    const double w = std::exp(pd.log_weight[h]);
    mass += w;
    mean += w * CellElevation(pd.cell[h]);
  }
  mean /= mass;
  const double sigma_h = Spacing() / 2;
  double var = 0;
  for (std::size_t h = 0; h < pd.cell.size(); ++h) {
    if (std::abs(pd.cell[h] - pd.cell[best]) > 1) continue;
    const double d = CellElevation(pd.cell[h]) - mean;
    var += std::exp(pd.log_weight[h]) / mass * (sigma_h * sigma_h + d * d);
  }
  return Collapse{mean, std::sqrt(var), mass / total};
}

std::pair<double, double> SonarEkf::FanMoments() const {
  const double sigma_h = Spacing() / 2;
  double var = 0;
  for (int c = 0; c < options_.hypotheses; ++c) var += CellElevation(c) * CellElevation(c);
  return {0.0, std::sqrt(sigma_h * sigma_h + var / options_.hypotheses)};
}

std::pair<double, int> SonarEkf::PromotePending(const std::vector<std::size_t>& which,
                                                const std::vector<std::pair<double, double>>& priors) {
  if (which.empty()) return {0.0, 0};
  // Enter every feature from its first view with its elevation prior...
  std::vector<NewFeature> nf;
  for (std::size_t j = 0; j < which.size(); ++j) {
    const Pending& pd = pending_[which[j]];
    const View& anchor = pd.views.front();
    const auto [phi, sigma_phi] = priors[j];
    NewFeature f;
    f.id = pd.id;
    f.first_step = anchor.step;
    f.observations = static_cast<int>(pd.views.size());
    f.pose_offset = anchor.step == step_ ? 0 : CloneOffset(anchor.step);
    Eigen::Matrix3d J_polar;
    f.mean =
        SonarBackProjectJacobians(x_.segment<6>(f.pose_offset), anchor.range, anchor.azimuth, phi, &f.J_pose, &J_polar);
    const Eigen::Vector3d var(anchor.sigma[0] * anchor.sigma[0], anchor.sigma[1] * anchor.sigma[1],
                              sigma_phi * sigma_phi);
    f.polar_cov = J_polar * var.asDiagonal() * J_polar.transpose();
    nf.push_back(f);
  }
  const FeatureBlocks blocks = MakeFeatureBlocks(nf, P_);
  const int base = Append(blocks.b, blocks.C, blocks.B);
  // ... then replay the later views against the poses they were taken from.
  std::vector<Obs> replay;
  for (std::size_t j = 0; j < which.size(); ++j) {
    const Pending& pd = pending_[which[j]];
    const int offset = base + 3 * static_cast<int>(j);
    features_[pd.id] = FeatureSlot{offset, nf[j].observations, nf[j].first_step};
    for (std::size_t v = 0; v < pd.views.size(); ++v) {
      const View& view = pd.views[v];
      if (v > 0) {
        replay.push_back(
            Obs{view.step == step_ ? 0 : CloneOffset(view.step), offset, view.range, view.azimuth, view.sigma});
      }
      for (Clone& c : clones_) {
        if (c.step == view.step) --c.users;
      }
    }
  }
  const double nis = replay.empty() ? 0.0 : Update(replay);
  std::vector<bool> drop(pending_.size(), false);
  for (std::size_t i : which) drop[i] = true;
  std::vector<Pending> keep;
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    if (!drop[i]) keep.push_back(std::move(pending_[i]));
  }
  pending_ = std::move(keep);
  return {nis, 2 * static_cast<int>(replay.size())};
}

void SonarEkf::ReleaseClones() {
  for (std::size_t i = clones_.size(); i-- > 0;) {
    if (clones_[i].users > 0) continue;
    const int offset = clones_[i].offset;
    clones_.erase(clones_.begin() + static_cast<std::ptrdiff_t>(i));
    RemoveBlock(offset, 6);
  }
}

SonarFeatureEstimate SonarEkf::PendingEstimate(const Pending& pd) const {
  // Moments of the hypothesis mixture seen from the first view's clone.
  const View& anchor = pd.views.front();
  const int a = CloneOffset(anchor.step);
  const Vector6d xa = x_.segment<6>(a);
  double sw = 0;
  for (double l : pd.log_weight) sw += std::exp(l);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double phi = 0;
  std::vector<Eigen::Vector3d> pts;
  for (std::size_t h = 0; h < pd.cell.size(); ++h) {
    const double w = std::exp(pd.log_weight[h]) / sw;
    pts.push_back(SonarBackProject<double>(xa, anchor.range, anchor.azimuth, CellElevation(pd.cell[h])));
    mean += w * pts.back();
    phi += w * CellElevation(pd.cell[h]);
  }
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (std::size_t h = 0; h < pd.cell.size(); ++h) {
    const Eigen::Vector3d d = pts[h] - mean;
    cov += std::exp(pd.log_weight[h]) / sw * d * d.transpose();
  }
  Eigen::Matrix<double, 3, 6> J_pose;
  Eigen::Matrix3d J_polar;
  SonarBackProjectJacobians(xa, anchor.range, anchor.azimuth, phi, &J_pose, &J_polar);
  const double sigma_h = Spacing() / 2;
  const Eigen::Vector3d var(anchor.sigma[0] * anchor.sigma[0], anchor.sigma[1] * anchor.sigma[1], sigma_h * sigma_h);
  cov += J_pose * P_.block<6, 6>(a, a) * J_pose.transpose() + J_polar * var.asDiagonal() * J_polar.transpose();
  SonarFeatureEstimate f;
  f.id = pd.id;
  f.position = mean;
  f.covariance = cov;
  f.in_state = false;
  f.observations = static_cast<int>(pd.views.size());
  f.first_step = anchor.step;
  return f;
}

}  // namespace hull
