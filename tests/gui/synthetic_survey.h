// A small survey made in code for the screenshot baselines (COLMAP's
// scene/synthetic.h habit): independent of the simulator's tuning, so the
// baselines change only when the views do.
//
// The hull is a 20 x 6 x 4 m box (z up in M, its bottom at z = 0) placed by
// x_gM = [0, 0, 5, pi, 0, 0.3] (bottom at 5 m depth, heading 0.3 rad); the
// vehicle flies three tracks 1.6 m below it looking up (servo pi/2); DVL
// ranges and feature pixels are exact for the true poses; the initial
// navigation drifts linearly. Truth: a cylinder, a box and a patch standing
// off the bottom, and a shallow dent (negative deviations).
#pragma once

#include <QString>
#include <memory>

#include "geometry/triangle_mesh.h"
#include "survey/survey.h"

namespace hull::ui::testing {

struct SyntheticSurvey {
  std::shared_ptr<const TriangleMesh> mesh;  // in M
  std::shared_ptr<const SurveyBundle> bundle;
};

const SyntheticSurvey& MakeSyntheticSurvey();

// Writes it as a bundle folder with its hull.ply; returns the folder.
QString WriteSyntheticSurvey(const QString& directory);

}  // namespace hull::ui::testing
