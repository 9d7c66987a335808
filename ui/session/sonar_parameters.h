// The sonar chain's tuning as rows of the parameter table (group "Sonar",
// keys "sonar_..."): the EKF's elevation hypotheses, the image chain's
// detector, gate and track life, the smoother's limits. Like every row they
// are saved in the project and undoable; a change runs the sonar dock's
// sequence again (nothing of the hull inspection). The dock's quick
// controls (feature source, initialisation, smoother on or off) stay on the
// dock.
#pragma once

#include <vector>

#include "sonar/sonar_pipeline.h"
#include "ui/session/parameters.h"

namespace hull::ui {

void AddSonarFields(ParameterTable& table);

// The pipeline's options with the table's values (the other fields keep
// SonarPipelineOptions' defaults; the source, initialisation and smoother
// switch are the dock's).
SonarPipelineOptions SonarTuningFrom(const ParameterValues& values);

// The sonar rows' values as one text: the dock runs again when it changes.
QString SonarKey(const ParameterValues& values);

// The values copied into the options and their Check(); an OptionError
// becomes the error of its row.
std::vector<ParameterError> CheckSonarParameters(const ParameterValues& values);

}  // namespace hull::ui
