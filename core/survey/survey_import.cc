#include "survey/survey_import.h"

#include <cstdlib>
#include <filesystem>
#include <functional>
#include <optional>

#include "base/error.h"
#include "plugin/plugin_registry.h"
#include "survey/survey_io.h"

namespace hull {
namespace fs = std::filesystem;
namespace {

// A bundle folder, or the survey.json in one: the folder; else empty.
fs::path BundleFolder(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec) && fs::exists(path / "survey.json", ec)) return path;
  if (path.filename() == "survey.json" && fs::is_regular_file(path, ec)) return path.parent_path();
  return {};
}

}  // namespace

std::string ImportedSurveyFolder() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  fs::path base = xdg && *xdg ? fs::path(xdg) : fs::path(home && *home ? home : "/tmp") / ".cache";
  return (base / "hullinspect" / "imported").string();
}

SurveyBundle OpenSurveyBundle(const std::string& path, std::vector<std::pair<std::string, std::string>>* report) {
  const fs::path bundle = BundleFolder(path);
  if (!bundle.empty()) return ReadSurveyBundle(bundle.string());
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError({path, 0, 0, ""}, "no such file or folder");
  const plugin::Registry& registry = plugin::Registry::Global();
  if (registry.BestSurveyScore(path) == plugin::kCannotRead) {
    throw InputError({path, 0, 0, ""},
                     "not a survey bundle (no survey.json) and no survey importer plugin reads it "
                     "(see 'hullinspect-cli plugins')");
  }
  // One folder per input: the name and a hash of the absolute path. A
  // conversion goes to a fresh sibling first, so a failed one leaves
  // nothing half-written behind.
  const fs::path absolute = fs::absolute(path).lexically_normal();
  const std::string key = absolute.filename().string() + "-" + std::to_string(std::hash<std::string>()(absolute));
  const fs::path target = fs::path(ImportedSurveyFolder()) / key;
  const fs::path partial = fs::path(target.string() + ".partial");
  fs::remove_all(partial, ec);
  fs::create_directories(partial);
  std::optional<plugin::Report> done;
  try {
    done = registry.ImportSurvey(path, partial.string());
  } catch (...) {
    fs::remove_all(partial, ec);
    throw;
  }
  fs::remove_all(target, ec);
  fs::rename(partial, target);
  if (report && done) *report = std::move(*done);
  return ReadSurveyBundle(target.string());
}

bool IsSurveyPath(const std::string& path) {
  return !BundleFolder(path).empty() || plugin::Registry::Global().BestSurveyScore(path) > plugin::kCannotRead;
}

}  // namespace hull
