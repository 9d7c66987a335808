// survey.json of a survey bundle: parsing, with the manifest's plausibility
// rules (survey_plausibility.h), and writing. Used by survey_io.cc; the
// public entry points are ParseSurveyManifest and SurveyManifestToJson there.
#pragma once

#include <string>
#include <string_view>

#include "base/json.h"
#include "survey/survey.h"

namespace hull::survey_manifest {

// Throws InputError naming the key at fault (the first problem).
SurveyManifest ParseManifest(const Json& doc, const std::string& file);
Json ManifestJson(const SurveyManifest& manifest);

// Helpers shared with the other survey files.
Json Vec(const Eigen::VectorXd& v);
void CheckPositive(const JsonReader& r, std::string_view key, double v);
Eigen::Vector3d NonZero3(const JsonReader& r, std::string_view key);

}  // namespace hull::survey_manifest
