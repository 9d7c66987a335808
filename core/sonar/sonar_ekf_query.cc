// The sonar EKF's queries for data association (predicted measurements and
// their covariances) and its feature management (ids, dropping a feature).
#include <algorithm>
#include <stdexcept>
#include <string>

#include "sonar/acoustic_camera.h"
#include "sonar/sonar_ekf.h"

namespace hull {

void SonarEkf::PredictMeasurements(const std::vector<std::int64_t>& ids, Eigen::VectorXd* z,
                                   Eigen::MatrixXd* HPHt) const {
  const int n = static_cast<int>(ids.size());
  // The pose and the features' rows of the state: H is non-zero only there.
  std::vector<int> rows = {0, 1, 2, 3, 4, 5};
  for (std::int64_t id : ids) {
    const int offset = FeatureOffset(id);
    if (offset < 0) {
      throw std::invalid_argument("SonarEkf::PredictMeasurements: feature " + std::to_string(id) +
                                  " is not in the state");
    }
    for (int a = 0; a < 3; ++a) rows.push_back(offset + a);
  }
  const int m = static_cast<int>(rows.size());
  Eigen::MatrixXd Psub(m, m);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) Psub(i, j) = P_(rows[static_cast<std::size_t>(i)], rows[static_cast<std::size_t>(j)]);
  }
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2 * n, m);
  z->resize(2 * n);
  for (int i = 0; i < n; ++i) {
    Eigen::Matrix<double, 2, 6> Hp;
    Eigen::Matrix<double, 2, 3> Hl;
    z->segment<2>(2 * i) =
        SonarMeasureJacobians(x_.head<6>(), x_.segment<3>(rows[static_cast<std::size_t>(6 + 3 * i)]), &Hp, &Hl);
    H.block<2, 6>(2 * i, 0) = Hp;
    H.block<2, 3>(2 * i, 6 + 3 * i) = Hl;
  }
  *HPHt = H * Psub * H.transpose();
  *HPHt = (0.5 * (*HPHt + HPHt->transpose())).eval();
}

std::vector<SonarEkf::HypothesisPrediction> SonarEkf::PredictPending(std::int64_t id) const {
  for (const Pending& pd : pending_) {
    if (pd.id == id) return HypothesisPredictions(pd);
  }
  throw std::invalid_argument("SonarEkf::PredictPending: feature " + std::to_string(id) + " is not waiting");
}

std::vector<std::int64_t> SonarEkf::FeatureIds() const {
  std::vector<std::int64_t> ids;
  for (const auto& [id, slot] : features_) ids.push_back(id);
  std::sort(ids.begin(), ids.end());
  return ids;
}

std::vector<std::int64_t> SonarEkf::PendingIds() const {
  std::vector<std::int64_t> ids;
  for (const Pending& pd : pending_) ids.push_back(pd.id);
  std::sort(ids.begin(), ids.end());
  return ids;
}

bool SonarEkf::DropFeature(std::int64_t id) {
  auto f = features_.find(id);
  if (f != features_.end()) {
    // Marginalising a Gaussian over a block removes its rows and columns.
    const int offset = f->second.offset;
    features_.erase(f);
    RemoveBlock(offset, 3);
    return true;
  }
  auto it = std::find_if(pending_.begin(), pending_.end(), [&](const Pending& p) { return p.id == id; });
  if (it == pending_.end()) return false;
  for (const View& view : it->views) {
    for (Clone& c : clones_) {
      if (c.step == view.step) --c.users;
    }
  }
  pending_.erase(it);
  ReleaseClones();
  return true;
}

}  // namespace hull
