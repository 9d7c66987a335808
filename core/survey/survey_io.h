// Reading, validating and writing survey bundles (versions 1 and 2; the
// images of version 2 are listed here, read and checked in survey_images.h).
#pragma once

#include <string>
#include <vector>

#include "base/error.h"
#include "survey/survey.h"

namespace hull {

// Reads a bundle folder; throws InputError (file, line, column, field and
// what was expected) at the first problem. Warnings are dropped.
SurveyBundle ReadSurveyBundle(const std::string& dir);

// Reads as much as it can and returns every problem found (errors and
// warnings), in file order. A bundle with no kError problem opens.
std::vector<Problem> ValidateSurveyBundle(const std::string& dir);

// As ValidateSurveyBundle, also returning what was read.
SurveyBundle ReadSurveyBundleCollecting(const std::string& dir, std::vector<Problem>* problems);

// Writes every file of the bundle (each atomically). Optional parts (landmarks,
// truth, sonar) are written when present. The mesh named by model_hint is not
// written here; the caller places it (see SaveMesh).
void WriteSurveyBundle(const SurveyBundle& bundle, const std::string& dir);

// Parses survey.json text alone (used by tests and the GUI's bundle preview).
SurveyManifest ParseSurveyManifest(const std::string& text, const std::string& file);
std::string SurveyManifestToJson(const SurveyManifest& manifest);

}  // namespace hull
