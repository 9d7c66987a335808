// hullinspect-cli validate: check a survey bundle or acoustic sequence.
#include <cstdio>
#include <filesystem>

#include "cli/args.h"
#include "cli/commands.h"
#include "survey/acoustic_sequence.h"
#include "survey/survey_io.h"

namespace hull::cli {
namespace {

const char* kHelp = R"(usage: hullinspect-cli validate PATH [--all]

Checks a survey bundle (a folder with survey.json) or an acoustic sequence (a
folder with sonar.json) against the survey contract, versions 1 and 2 (version
2: every image in images/ is decoded and checked for its size and a bit depth
and channel count shared by all; a missing image is a dropped frame, a
warning). Prints a summary and the first problems; --all prints every problem.
Each problem names the file, line, column and field. --quiet is accepted, as
by every command (validate prints no progress).

exit codes: 0 valid (warnings allowed), 2 bad command line, 3 errors found
(malformed or implausible input: the status run, adjust and the other
commands give for the same bundle)
)";

}  // namespace

int RunValidate(const CommandArgs& argv) {
  Args a(argv, {"all", "quiet"});
  if (a.Has("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  a.AllowOnly({"all", "quiet"});
  if (a.positionals().size() != 1) throw UsageError("expected one bundle or sequence folder");
  const std::string path = a.positionals()[0];
  namespace fs = std::filesystem;
  std::vector<Problem> problems;
  const bool sonar_only = fs::exists(fs::path(path) / "sonar.json") && !fs::exists(fs::path(path) / "survey.json");
  problems = sonar_only ? ValidateAcousticSequence(path) : ValidateSurveyBundle(path);
  int errors = 0, warnings = 0;
  for (const auto& p : problems) (p.severity == Severity::kError ? errors : warnings)++;
  const std::size_t limit = a.Has("all") ? problems.size() : 20;
  for (std::size_t i = 0; i < problems.size() && i < limit; ++i) std::printf("%s\n", problems[i].ToString().c_str());
  if (problems.size() > limit) {
    std::printf("... %zu more (use --all to list every problem)\n", problems.size() - limit);
  }
  std::printf("%s: %s (%d errors, %d warnings)\n", path.c_str(), errors ? "INVALID" : "valid", errors, warnings);
  return errors ? kExitBadInput : kExitOk;
}

}  // namespace hull::cli
