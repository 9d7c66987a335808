// Small simulated survey bundles for tests that need a whole survey on disk
// (validate -> align -> adjust in seconds): the demo preset shrunk to two
// tracks along the middle of the parametric hull, with truth and hull.ply.
#pragma once

#include <string>

#include "simulate/survey_simulator.h"

namespace hull::test {

// The demo preset, shrunk: about 40 keyframes, a few hundred landmarks.
SurveySimulationOptions SmallSurveyOptions(std::uint64_t seed = 7);
// Simulates it once per process (cached) and returns it.
const SimulatedSurvey& SmallSurvey();
// Writes the small survey (bundle and hull.ply) into dir.
void WriteSmallSurvey(const std::string& dir);

}  // namespace hull::test
