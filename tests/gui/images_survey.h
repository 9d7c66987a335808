// A small version 2 survey for the images view's tests and the user guide:
// the demo preset's stereo rig at half the HAUV's resolution (680x512) over
// a short stretch of the keel, its images rendered by the simulator, and no
// features.csv (so opening it runs the visual front end).
#pragma once

#include <QString>

namespace hull::ui::testing {

// Simulates and writes it once per process under OutputDir(); returns the
// bundle folder (its hull.ply beside survey.json as model_hint).
QString ImagesSurveyDir();

}  // namespace hull::ui::testing
