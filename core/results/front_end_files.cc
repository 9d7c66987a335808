#include "results/front_end_files.h"

#include <filesystem>

#include "base/csv.h"
#include "base/file_io.h"
#include "survey/survey_io.h"

namespace hull {
namespace fs = std::filesystem;

void WriteFrontEndResult(const FrontEndResult& r, const SurveyManifest& manifest, const std::string& features_csv) {
  const fs::path path(features_csv);
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  WriteFileAtomic(features_csv, FeaturesCsvText(r.features, manifest.camera.stereo()));
  CsvWriter w({"from", "to", "method", "putative", "inliers", "accepted", "note", "kind", "overlap", "window"});
  for (const auto& p : r.pairs) {
    w.Add(p.from).Add(p.to).Add(p.stereo ? "rigid" : "essential").Add(p.putative).Add(p.inliers);
    w.Add(p.accepted ? "1" : "0").Add(p.note).Add(p.loop ? "loop" : "sequential");
    if (p.loop) {
      w.Add(p.overlap);
    } else {
      w.Add("");
    }
    w.Add(p.window);
    w.EndRow();
  }
  WriteFileAtomic((path.parent_path() / "match-graph.csv").string(), w.text());
}

}  // namespace hull
