// Test scenes of the mapping tests: a 3 x 3 grid of keyframes under a
// patch of hull.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <utility>

#include "geometry/pose.h"
#include "mapping/mapping_input.h"

namespace hull {

// Nine keyframes 1.5 m below z = 0 of g, looking up along +z (identity
// rotation), at first + (i, j) * step for i, j in 0..2, ids first_id + 3 i
// + j; each observes every landmark of `in` in front of it and inside its
// top image.
inline void AddKeyframeGrid(MappingInput& in, std::int64_t first_id, const Eigen::Vector2d& first,
                            const Eigen::Vector2d& step) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      MappingKeyframe k;
      k.id = first_id + 3 * i + j;
      k.x_g_cT =
          Pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(first.x() + step.x() * i, first.y() + step.y() * j, -1.5));
      const Pose inv = k.x_g_cT.Inverse();
      for (std::size_t l = 0; l < in.landmarks.size(); ++l) {
        const Eigen::Vector3d p = inv * in.landmarks[l].p_g;
        if (p.z() > 0 && in.camera.InImage(in.camera.top.Project(p))) k.landmarks.push_back(static_cast<int>(l));
      }
      in.keyframes.push_back(std::move(k));
    }
  }
}

}  // namespace hull
