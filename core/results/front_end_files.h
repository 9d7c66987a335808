// The visual front end's files (docs/vision.md, docs/results-format.md
// "Pipeline results"): features.csv (the survey contract's version 1
// feature observations) and, beside it, match-graph.csv. Written by
// `hullinspect-cli features` into a bundle (or --out FILE) and by `run`
// into RESULTS/features/ when the front end ran.
#pragma once

#include <string>

#include "survey/survey_manifest.h"
#include "vision/front_end.h"

namespace hull {

// Writes `features_csv` and, beside it, match-graph.csv (from,to,method,
// putative,inliers,accepted,note,kind,overlap,window; kind is `sequential`
// or `loop`, overlap the loop's predicted footprint overlap, window the
// search radius in px). Each atomically; the folder is created when needed.
void WriteFrontEndResult(const FrontEndResult& result, const SurveyManifest& manifest, const std::string& features_csv);

}  // namespace hull
