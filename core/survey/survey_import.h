// Opening a survey from what the user names: a survey bundle folder as it
// is, or a foreign survey log that a survey importer plugin
// (plugin::SurveyImporter) converts into a bundle first.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "survey/survey.h"

namespace hull {

// A folder holding survey.json is read with ReadSurveyBundle. Anything else
// a plugin's survey importer reads is converted into a fresh bundle under
// ImportedSurveyFolder() and read from there (`report`, when given,
// receives what the importer reported). Throws InputError naming the path
// when neither applies or the input is malformed.
SurveyBundle OpenSurveyBundle(const std::string& path,
                              std::vector<std::pair<std::string, std::string>>* report = nullptr);

// True when `path` is a bundle folder (or its survey.json) or a survey
// importer plugin reads it.
bool IsSurveyPath(const std::string& path);

// Where converted surveys are written: $XDG_CACHE_HOME/hullinspect/imported
// (by default ~/.cache/hullinspect/imported), one folder per input path.
std::string ImportedSurveyFolder();

}  // namespace hull
