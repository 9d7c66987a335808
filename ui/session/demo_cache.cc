#include "ui/session/demo_cache.h"

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "demo_fingerprint.h"
#include "simulate/survey_simulator.h"
#include "survey/survey_io.h"

namespace hull::ui {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStampFile = "hullinspect-demo.stamp";

std::string StampText() {
  const SurveySimulationOptions options = SurveyPreset("demo");
  std::ostringstream s;
  s << "hullinspect demo cache 1\npreset demo\nseed " << options.seed << "\nversion " << HI_VERSION << "\nsimulator "
    << HI_DEMO_FINGERPRINT << "\n";
  return s.str();
}

std::string ReadSmallFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Removes a temporary folder unless released.
class TemporaryFolder {
 public:
  explicit TemporaryFolder(fs::path path) : path_(std::move(path)) {}
  ~TemporaryFolder() {
    if (path_.empty()) return;
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  const fs::path& path() const { return path_; }
  void Release() { path_.clear(); }

 private:
  fs::path path_;
};

}  // namespace

std::string DemoDirectory(const std::string& cache_root) {
  return (fs::path(cache_root) / ("demo-" + std::to_string(SurveyPreset("demo").seed))).string();
}

bool IsValidDemo(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec) || !fs::is_regular_file(fs::path(dir) / "hull.ply", ec)) return false;
  if (ReadSmallFile(fs::path(dir) / kStampFile) != StampText()) return false;
  for (const Problem& p : ValidateSurveyBundle(dir)) {
    if (p.severity == Severity::kError) return false;
  }
  return true;
}

DemoFiles PrepareDemo(const std::string& cache_root, Progress& progress) {
  DemoFiles files;
  files.directory = DemoDirectory(cache_root);
  files.mesh = (fs::path(files.directory) / "hull.ply").string();
  progress.Update(0.0, "checking the cached demo survey");
  if (IsValidDemo(files.directory)) return files;

  fs::create_directories(cache_root);
  std::random_device entropy;
  const fs::path target(files.directory);
  TemporaryFolder temp(target.string() + ".partial-" + std::to_string(entropy()));
  SubProgress simulate(progress, 0.0, 0.9);
  const SimulatedSurvey survey = SimulateSurvey(SurveyPreset("demo"), simulate);
  progress.ThrowIfCancelled();
  progress.Update(0.9, "writing the demo survey");
  WriteSimulatedSurvey(survey, temp.path().string());
  {
    std::ofstream stamp(temp.path() / kStampFile, std::ios::binary);
    stamp << StampText();
    if (!stamp) throw std::runtime_error("cannot write " + (temp.path() / kStampFile).string());
  }
  progress.ThrowIfCancelled();
  // Never remove a valid copy (another instance may be reading it): move
  // ours into place, and only replace what is there when it is broken.
  std::error_code ec;
  fs::rename(temp.path(), target, ec);
  if (ec) {
    if (IsValidDemo(files.directory)) return files;  // another instance finished first
    fs::remove_all(target, ec);
    ec.clear();
    fs::rename(temp.path(), target, ec);
    if (ec) {
      if (IsValidDemo(files.directory)) return files;
      throw std::runtime_error("cannot move the demo survey into " + target.string() + ": " + ec.message());
    }
  }
  temp.Release();
  files.simulated = true;
  progress.Update(1.0, "demo survey ready");
  return files;
}

}  // namespace hull::ui
