#include "vision/camera_geometry.h"

#include <Eigen/SVD>
#include <cmath>
#include <stdexcept>

namespace hull {

Eigen::Matrix3d CameraMatrix(const PinholeIntrinsics& k) {
  Eigen::Matrix3d K;
  K << k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1;
  return K;
}

Pose CameraPoseFromNav(const SurveyManifest& m, const NavRecord& nav, bool bottom_camera) {
  const Pose top = Pose::FromVector(nav.x_gv) * m.VehicleToServo(nav.servo) * Pose::FromVector(m.camera.servo_to_top);
  return bottom_camera ? top * Pose::FromVector(m.camera.top_to_bottom) : top;
}

namespace {
Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}
}  // namespace

Eigen::Matrix3d FundamentalMatrix(const Eigen::Matrix3d& K1, const Eigen::Matrix3d& K2, const Pose& x_c1_c2) {
  // p2 = R21 p1 + t21 with x_c2_c1 = (-)x_c1_c2; E = [t21]x R21.
  const Pose x_c2_c1 = x_c1_c2.Inverse();
  const Eigen::Matrix3d E = Skew(x_c2_c1.translation()) * x_c2_c1.rotation();
  return K2.inverse().transpose() * E * K1.inverse();
}

double EpipolarDistance(const Eigen::Matrix3d& F, const Eigen::Vector2d& x1, const Eigen::Vector2d& x2) {
  const Eigen::Vector3d l = F * x1.homogeneous();
  const double n = std::hypot(l.x(), l.y());
  if (!(n > 0)) return std::numeric_limits<double>::infinity();
  return std::abs(l.dot(x2.homogeneous())) / n;
}

Eigen::Vector3d TriangulateDlt(const Eigen::Matrix<double, 3, 4>& P1, const Eigen::Matrix<double, 3, 4>& P2,
                               const Eigen::Vector2d& x1, const Eigen::Vector2d& x2) {
  Eigen::Matrix4d A;
  A.row(0) = x1.x() * P1.row(2) - P1.row(0);
  A.row(1) = x1.y() * P1.row(2) - P1.row(1);
  A.row(2) = x2.x() * P2.row(2) - P2.row(0);
  A.row(3) = x2.y() * P2.row(2) - P2.row(1);
  Eigen::JacobiSVD<Eigen::Matrix4d> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d X = svd.matrixV().col(3);
  return X.head<3>() / X.w();
}

Eigen::Matrix<double, 3, 4> ProjectionMatrix(const Eigen::Matrix3d& K, const Pose& x_w_c) {
  const Pose x_c_w = x_w_c.Inverse();
  Eigen::Matrix<double, 3, 4> Rt;
  Rt.leftCols<3>() = x_c_w.rotation();
  Rt.col(3) = x_c_w.translation();
  return K * Rt;
}

Pose AlignRigid(const std::vector<Eigen::Vector3d>& src, const std::vector<Eigen::Vector3d>& dst) {
  if (src.size() != dst.size() || src.size() < 3) throw std::invalid_argument("AlignRigid: needs >= 3 point pairs");
  const double n = static_cast<double>(src.size());
  Eigen::Vector3d ms = Eigen::Vector3d::Zero(), md = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < src.size(); ++i) {
    ms += src[i];
    md += dst[i];
  }
  ms /= n;
  md /= n;
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();  // cross-covariance sum (dst - md)(src - ms)^T
  for (std::size_t i = 0; i < src.size(); ++i) H += (dst[i] - md) * (src[i] - ms).transpose();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0) S(2, 2) = -1;  // no reflection
  const Eigen::Matrix3d R = svd.matrixU() * S * svd.matrixV().transpose();
  return Pose(R, md - R * ms);
}

double AngleBetweenDirections(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace hull
