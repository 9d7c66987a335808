#include "support/test_surveys.h"

namespace hull::test {

SurveySimulationOptions SmallSurveyOptions(std::uint64_t seed) {
  SurveySimulationOptions o = SurveyPreset("demo");
  o.name = "Small test survey";
  o.seed = seed;
  o.plan.half_width = 0.4;  // two bottom tracks
  o.plan.track_spacing = 0.8;
  o.plan.keyframe_spacing = 0.6;
  o.hull_feature_density = 10;
  o.object_feature_density = 100;
  return o;
}

const SimulatedSurvey& SmallSurvey() {
  static const SimulatedSurvey survey = [] {
    NullProgress p;
    return SimulateSurvey(SmallSurveyOptions(), p);
  }();
  return survey;
}

void WriteSmallSurvey(const std::string& dir) { WriteSimulatedSurvey(SmallSurvey(), dir); }

}  // namespace hull::test
