#include "sonar/sonar_ekf.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_set>

#include "base/error.h"
#include "sonar/acoustic_camera.h"

namespace hull {
namespace {

// Columns [c, c + W) of a symmetric matrix of which only the lower triangle is current.
template <int W>
Eigen::Matrix<double, Eigen::Dynamic, W> LowerColumns(const Eigen::MatrixXd& P, int c) {
  const Eigen::Index N = P.rows();
  Eigen::Matrix<double, Eigen::Dynamic, W> out(N, W);
  for (int j = 0; j < W; ++j) {
    const int col = c + j;
    out.col(j).head(col) = P.row(col).head(col).transpose();
    out.col(j).tail(N - col) = P.col(col).tail(N - col);
  }
  return out;
}

void WrapPoseAngles(Eigen::VectorXd& x, int offset) {
  for (int i = 3; i < 6; ++i) x[offset + i] = WrapAngle(x[offset + i]);
}

}  // namespace

SonarEkf::SonarEkf(const SonarSensor& sensor, const SonarMotionNoise& motion_noise, const Vector6d& initial_pose,
                   const Vector6d& initial_pose_sigma, SonarEkfOptions options)
    : sensor_(sensor), motion_noise_(motion_noise), options_(options) {
  std::string why;
  if (!options_.Check(&why)) {
    const auto colon = why.find(':');
    throw OptionError(why.substr(0, colon), why.substr(colon + 2));
  }
  if (!(initial_pose_sigma.array() > 0).all()) {
    throw std::invalid_argument("SonarEkf: every initial pose standard deviation must be positive");
  }
  x_ = initial_pose;
  WrapPoseAngles(x_, 0);
  P_ = initial_pose_sigma.array().square().matrix().asDiagonal();
}

SonarEkf::SonarEkf(const AcousticSequence& seq, SonarEkfOptions options)
    : SonarEkf(seq.sensor, seq.motion_noise, seq.initial_pose, seq.initial_pose_sigma, options) {}

int SonarEkf::FeatureOffset(std::int64_t id) const {
  auto it = features_.find(id);
  return it == features_.end() ? -1 : it->second.offset;
}

SonarStepEstimate SonarEkf::Step(const SonarControl* control, const std::vector<SonarMeasurement>& measurements) {
  if (!predicted_) CheckMeasurements(measurements, step_ + 1);  // refuse before changing anything
  Predict(control);
  return Correct(measurements);
}

void SonarEkf::Predict(const SonarControl* control) {
  if (predicted_)
    throw std::invalid_argument("SonarEkf::Predict: step " + std::to_string(step_) + " was not corrected");
  if (step_ < 0 && control) throw std::invalid_argument("SonarEkf::Step: the first step has no control");
  if (step_ >= 0 && !control) {
    throw std::invalid_argument("SonarEkf::Step: step " + std::to_string(step_ + 1) + " needs its control");
  }
  if (control && control->step != step_ + 1) {
    throw std::invalid_argument("SonarEkf::Step: control for step " + std::to_string(control->step) +
                                " given at step " + std::to_string(step_ + 1));
  }
  if (control && !control->u.allFinite()) throw std::invalid_argument("SonarEkf::Step: control is not finite");
  ++step_;
  predicted_ = true;
  if (control) PredictPose(*control);
}

Eigen::Vector2d SonarEkf::NoiseOf(const SonarMeasurement& m) const {
  return {m.range_sigma > 0 ? m.range_sigma : sensor_.range_sigma,
          m.azimuth_sigma > 0 ? m.azimuth_sigma : sensor_.azimuth_sigma};
}

void SonarEkf::CheckMeasurements(const std::vector<SonarMeasurement>& measurements, std::int64_t step) const {
  std::unordered_set<std::int64_t> ids;
  for (const SonarMeasurement& m : measurements) {
    if (m.step != step) {
      throw std::invalid_argument("SonarEkf::Step: a measurement of step " + std::to_string(m.step) +
                                  " given at step " + std::to_string(step));
    }
    if (!ids.insert(m.feature).second) {
      throw std::invalid_argument("SonarEkf::Step: feature " + std::to_string(m.feature) + " measured twice");
    }
    if (!std::isfinite(m.range) || !std::isfinite(m.azimuth) || m.range <= 0 || !(m.range_sigma >= 0) ||
        !(m.azimuth_sigma >= 0) || !std::isfinite(m.range_sigma) || !std::isfinite(m.azimuth_sigma)) {
      throw std::invalid_argument("SonarEkf::Step: measurement of feature " + std::to_string(m.feature) +
                                  " is not a finite positive range and finite azimuth with finite sigmas");
    }
  }
}

SonarStepEstimate SonarEkf::Correct(const std::vector<SonarMeasurement>& measurements) {
  if (!predicted_) throw std::invalid_argument("SonarEkf::Correct: call Predict first");
  CheckMeasurements(measurements, step_);
  predicted_ = false;

  std::vector<Obs> in_state;
  std::vector<const SonarMeasurement*> fresh;
  std::vector<std::pair<std::size_t, const SonarMeasurement*>> waiting;
  for (const SonarMeasurement& m : measurements) {
    auto f = features_.find(m.feature);
    if (f != features_.end()) {
      in_state.push_back(Obs{0, f->second.offset, m.range, m.azimuth, NoiseOf(m)});
      ++f->second.observations;
      continue;
    }
    auto it = std::find_if(pending_.begin(), pending_.end(), [&](const Pending& p) { return p.id == m.feature; });
    if (it != pending_.end()) {
      waiting.emplace_back(static_cast<std::size_t>(it - pending_.begin()), &m);
    } else {
      fresh.push_back(&m);
    }
  }

  SonarStepEstimate out;
  out.step = step_;
  out.measurements = static_cast<int>(measurements.size());
  if (!in_state.empty()) {
    out.nis = Update(in_state);
    out.nis_dof = 2 * static_cast<int>(in_state.size());
    out.updated = static_cast<int>(in_state.size());
  }
  const int before = num_features_in_state();
  if (options_.init == SonarInit::kPaper && options_.confirm_views <= 1) {
    InitialisePaper(fresh);
  } else {
    // Weigh the waiting features' hypotheses with this view and remember it.
    for (auto& [index, m] : waiting) {
      WeighPending(pending_[index], *m);
      pending_[index].views.push_back(View{step_, m->range, m->azimuth, NoiseOf(*m)});
    }
    std::vector<std::size_t> ready;
    std::vector<std::pair<double, double>> priors;
    for (std::size_t i = 0; i < pending_.size(); ++i) {
      const Pending& pd = pending_[i];
      if (static_cast<int>(pd.views.size()) < options_.confirm_views) continue;
      if (options_.init == SonarInit::kPaper) {
        ready.push_back(i);
        priors.emplace_back(0.0, options_.paper_elevation_sigma_fraction * sensor_.elevation_fov);
        continue;
      }
      const Collapse c = CollapseOf(pd);
      const int extra_views = static_cast<int>(pd.views.size()) - 1;
      if (extra_views >= options_.min_extra_views && c.mass >= options_.collapse_probability) {
        ready.push_back(i);
        priors.emplace_back(c.phi, c.sigma);
      } else if (step_ - pd.views.front().step >= options_.max_delay_steps) {
        ready.push_back(i);
        priors.push_back(FanMoments());
      }
    }
    const auto [nis, dof] = PromotePending(ready, priors);
    out.nis += nis;
    out.nis_dof += dof;
    out.updated += dof / 2;
    // Features still waiting that were seen now, and new ones, need this pose kept.
    bool need_clone = !fresh.empty();
    for (const Pending& pd : pending_) need_clone = need_clone || pd.views.back().step == step_;
    if (need_clone) EnsureClone();
    for (Pending& pd : pending_) {
      if (pd.views.back().step == step_) ++clones_.back().users;
    }
    for (const SonarMeasurement* m : fresh) {
      Pending pd;
      pd.id = m->feature;
      pd.views.push_back(View{step_, m->range, m->azimuth, NoiseOf(*m)});
      for (int c = 0; c < options_.hypotheses; ++c) {
        pd.cell.push_back(c);
        pd.log_weight.push_back(0.0);
      }
      pending_.push_back(std::move(pd));
      ++clones_.back().users;
    }
    ReleaseClones();
  }
  out.initialised = num_features_in_state() - before;
  out.pending = num_pending();
  out.pose = pose();
  out.pose_covariance = pose_covariance();
  return out;
}

void SonarEkf::PredictPose(const SonarControl& control) {
  Matrix6d G, Gu;
  const Vector6d pose = SonarMotion(x_.head<6>(), control.u, &G, &Gu);
  const Vector6d sigma = ControlSigma(motion_noise_, control.u);
  const Matrix6d R = Gu * sigma.array().square().matrix().asDiagonal() * Gu.transpose();
  x_.head<6>() = pose;
  // P^ = G P G^T + R with G the identity outside the pose block: only the
  // pose rows and columns change (O(N)).
  Eigen::MatrixXd top = G * P_.topRows<6>();
  const Matrix6d Ppp = top.leftCols<6>() * G.transpose() + R;
  top.leftCols<6>() = 0.5 * (Ppp + Ppp.transpose());
  P_.topRows<6>() = top;
  P_.leftCols<6>() = top.transpose();
}

double SonarEkf::Update(const std::vector<Obs>& obs) {
  const int k = static_cast<int>(obs.size());
  const Eigen::Index N = x_.size();
  // Linearise every measurement once, at the predicted state x^ (eq. 8).
  // H has non-zeros only in each measurement's pose block (6 columns) and
  // feature block (3 columns): keep those 2x6 and 2x3 pieces instead of the
  // m x N matrix.
  std::vector<Eigen::Matrix<double, 2, 6>> Hp(static_cast<std::size_t>(k));
  std::vector<Eigen::Matrix<double, 2, 3>> Hl(static_cast<std::size_t>(k));
  std::vector<Eigen::Vector2d> innovation(static_cast<std::size_t>(k));
  for (int i = 0; i < k; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    const Obs& o = obs[ui];
    const Eigen::Vector2d z_hat =
        SonarMeasureJacobians(x_.segment<6>(o.pose_offset), x_.segment<3>(o.feature_offset), &Hp[ui], &Hl[ui]);
    innovation[ui] = Eigen::Vector2d(o.range - z_hat[0], WrapAngle(o.azimuth - z_hat[1]));
  }
  const Eigen::VectorXd x_bar = x_;
  // The measurements are independent given the state, so processing them in
  // blocks with the same linearisation gives exactly the batch update of eq.
  // 11-13, with the innovation of a later block taken through the linear
  // model, z - h(x^) - H (x - x^). Blocks keep the m x m solves small; each
  // block costs O(N^2 m_b). Only the lower triangle of P is kept current
  // until the end.
  const int block = options_.update_block;
  double nis = 0;
  for (int b0 = 0; b0 < k; b0 += block) {
    const int kb = std::min(block, k - b0), m = 2 * kb;
    Eigen::VectorXd nu(m);
    for (int i = 0; i < kb; ++i) {
      const auto ui = static_cast<std::size_t>(b0 + i);
      const Obs& o = obs[ui];
      Vector6d dpose = x_.segment<6>(o.pose_offset) - x_bar.segment<6>(o.pose_offset);
      for (int a = 3; a < 6; ++a) dpose[a] = WrapAngle(dpose[a]);
      const Eigen::Vector3d dl = x_.segment<3>(o.feature_offset) - x_bar.segment<3>(o.feature_offset);
      nu.segment<2>(2 * i) = innovation[ui] - Hp[ui] * dpose - Hl[ui] * dl;
      nu[2 * i + 1] = WrapAngle(nu[2 * i + 1]);
    }
    // M = P H^T (N x m): 9 columns of P per measurement (the pose columns
    // once per distinct pose block).
    std::vector<std::pair<int, Eigen::Matrix<double, Eigen::Dynamic, 6>>> pose_cols;
    Eigen::MatrixXd M(N, m);
    for (int i = 0; i < kb; ++i) {
      const Obs& o = obs[static_cast<std::size_t>(b0 + i)];
      auto it =
          std::find_if(pose_cols.begin(), pose_cols.end(), [&](const auto& c) { return c.first == o.pose_offset; });
      if (it == pose_cols.end()) {
        pose_cols.emplace_back(o.pose_offset, LowerColumns<6>(P_, o.pose_offset));
        it = pose_cols.end() - 1;
      }
      const auto ui = static_cast<std::size_t>(b0 + i);
      M.middleCols<2>(2 * i).noalias() = it->second * Hp[ui].transpose();
      M.middleCols<2>(2 * i).noalias() += LowerColumns<3>(P_, o.feature_offset) * Hl[ui].transpose();
    }
    // S = H P H^T + Q (m x m).
    Eigen::MatrixXd S(m, m);
    for (int i = 0; i < kb; ++i) {
      const auto ui = static_cast<std::size_t>(b0 + i);
      S.middleRows<2>(2 * i).noalias() = Hp[ui] * M.middleRows<6>(obs[ui].pose_offset);
      S.middleRows<2>(2 * i).noalias() += Hl[ui] * M.middleRows<3>(obs[ui].feature_offset);
    }
    S = (0.5 * (S + S.transpose())).eval();
    for (int i = 0; i < kb; ++i) {
      const Eigen::Vector2d& sigma = obs[static_cast<std::size_t>(b0 + i)].sigma;
      S(2 * i, 2 * i) += sigma[0] * sigma[0];
      S(2 * i + 1, 2 * i + 1) += sigma[1] * sigma[1];
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(S);
    if (llt.info() != Eigen::Success) {
      throw SonarNumericalError(step_, "the innovation covariance is not positive definite");
    }
    // W = L^-1 M^T with S = L L^T: M S^-1 M^T = W^T W, K^T = L^-T W.
    const Eigen::MatrixXd W = llt.matrixL().solve(M.transpose());
    const Eigen::VectorXd w = llt.matrixL().solve(nu);
    nis += w.squaredNorm();
    if (options_.joseph) {
      // Joseph form (I - KH) P (I - KH)^T + K Q K^T = P - K M^T - M K^T + K S K^T
      //   = P - K Z^T - Z K^T with Z = M - K S / 2: valid for any gain and,
      // unlike the short form, insensitive to first order to errors in K.
      // One symmetric rank-2m correction of the lower triangle.
      const Eigen::MatrixXd K = llt.matrixU().solve(W).transpose();
      x_.noalias() += K * nu;
      Eigen::MatrixXd A(N, 2 * m), B(N, 2 * m);
      A.leftCols(m) = K;
      A.rightCols(m).noalias() = M - 0.5 * K * S;
      B.leftCols(m) = A.rightCols(m);
      B.rightCols(m) = K;
      P_.triangularView<Eigen::Lower>() -= A * B.transpose();
    } else {
      // Short form P - M S^-1 M^T = P - W^T W (a symmetric rank-m downdate).
      x_.noalias() += W.transpose() * w;
      P_.selfadjointView<Eigen::Lower>().rankUpdate(W.transpose(), -1.0);
    }
  }
  WrapPoseAngles(x_, 0);
  for (const Clone& c : clones_) WrapPoseAngles(x_, c.offset);
  P_.triangularView<Eigen::StrictlyUpper>() = P_.transpose();
  for (Eigen::Index i = 0; i < N; ++i) {
    if (!(P_(i, i) > 0) || !std::isfinite(P_(i, i))) {
      throw SonarNumericalError(step_, "the covariance lost positive definiteness");
    }
  }
  return nis;
}

int SonarEkf::Append(const Eigen::VectorXd& b, const Eigen::MatrixXd& C, const Eigen::MatrixXd& B_bb) {
  const Eigen::Index N = x_.size(), n = b.size();
  x_.conservativeResize(N + n);
  x_.tail(n) = b;
  P_.conservativeResize(N + n, N + n);
  P_.bottomLeftCorner(n, N) = C;
  P_.topRightCorner(N, n) = C.transpose();
  P_.bottomRightCorner(n, n) = 0.5 * (B_bb + B_bb.transpose());
  return static_cast<int>(N);
}

void SonarEkf::RemoveBlock(int offset, int size) {
  const Eigen::Index N = x_.size();
  const Eigen::Index tail = N - offset - size;
  if (tail > 0) {
    x_.segment(offset, tail) = x_.tail(tail).eval();
    P_.middleRows(offset, tail) = P_.bottomRows(tail).eval();
    P_.middleCols(offset, tail) = P_.rightCols(tail).eval();
  }
  x_.conservativeResize(N - size);
  P_.conservativeResize(N - size, N - size);
  for (auto& [id, slot] : features_) {
    if (slot.offset > offset) slot.offset -= size;
  }
  for (Clone& c : clones_) {
    if (c.offset > offset) c.offset -= size;
  }
}

std::vector<SonarFeatureEstimate> SonarEkf::Features() const {
  std::vector<SonarFeatureEstimate> out;
  out.reserve(features_.size() + pending_.size());
  for (const auto& [id, slot] : features_) {
    SonarFeatureEstimate f;
    f.id = id;
    f.position = x_.segment<3>(slot.offset);
    f.covariance = P_.block<3, 3>(slot.offset, slot.offset);
    f.in_state = true;
    f.observations = slot.observations;
    f.first_step = slot.first_step;
    out.push_back(f);
  }
  for (const Pending& pd : pending_) out.push_back(PendingEstimate(pd));
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  return out;
}

std::optional<SonarFeatureEstimate> SonarEkf::Feature(std::int64_t id) const {
  auto it = features_.find(id);
  if (it != features_.end()) {
    SonarFeatureEstimate f;
    f.id = id;
    f.position = x_.segment<3>(it->second.offset);
    f.covariance = P_.block<3, 3>(it->second.offset, it->second.offset);
    f.observations = it->second.observations;
    f.first_step = it->second.first_step;
    return f;
  }
  for (const Pending& pd : pending_) {
    if (pd.id == id) return PendingEstimate(pd);
  }
  return std::nullopt;
}

}  // namespace hull
