// Two-view geometry of the survey's cameras: poses from the navigation,
// the calibrated rig's fundamental matrix, epipolar distances, linear
// (DLT) triangulation and the closed-form rigid alignment of two point
// clouds (Arun / Umeyama without scale). Checked against OpenCV's
// triangulatePoints and estimateAffine3D in tests/unit/vision.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "geometry/pose.h"
#include "survey/survey.h"

namespace hull {

// K of a pinhole camera.
Eigen::Matrix3d CameraMatrix(const PinholeIntrinsics& k);

// x_g_cT (or x_g_cB) of a keyframe from its nav row: x_gv (+) x_vs(servo)
// (+) servo_to_top [(+) top_to_bottom]; nominal extrinsics.
Pose CameraPoseFromNav(const SurveyManifest& manifest, const NavRecord& nav, bool bottom_camera = false);

// F with x2^T F x1 = 0 for pixels x1 of camera 1 and x2 of camera 2, where
// x_c1_c2 places camera 2 in camera 1.
Eigen::Matrix3d FundamentalMatrix(const Eigen::Matrix3d& K1, const Eigen::Matrix3d& K2, const Pose& x_c1_c2);

// Distance (px) of x2 to the epipolar line F x1 in image 2.
double EpipolarDistance(const Eigen::Matrix3d& F, const Eigen::Vector2d& x1, const Eigen::Vector2d& x2);

// Linear triangulation (DLT, the SVD of the 4x4 system, as
// cv::triangulatePoints) from two 3x4 projection matrices P = K [R | t]
// that map points of a common frame to pixels. Returns that frame's point.
Eigen::Vector3d TriangulateDlt(const Eigen::Matrix<double, 3, 4>& P1, const Eigen::Matrix<double, 3, 4>& P2,
                               const Eigen::Vector2d& x1, const Eigen::Vector2d& x2);

// P = K [R | t] of a camera placed at x_w_c in a frame w (maps w to pixels).
Eigen::Matrix<double, 3, 4> ProjectionMatrix(const Eigen::Matrix3d& K, const Pose& x_w_c);

// The rigid transform T (dst ~ T * src) minimising sum |dst - R src - t|^2
// (Arun et al. 1987, with Umeyama's reflection fix). Needs >= 3 points, not
// all collinear (then the rotation about the line is arbitrary).
Pose AlignRigid(const std::vector<Eigen::Vector3d>& src, const std::vector<Eigen::Vector3d>& dst);

// Angle (rad) between two directions.
double AngleBetweenDirections(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

}  // namespace hull
