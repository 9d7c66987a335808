// A small command-line parser for hullinspect-cli's sub-commands:
// "--name value", "--name=value", boolean "--flag", and positionals.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace hull::cli {

// Exit codes of hullinspect-cli (documented in --help and the README).
enum ExitCode : int {
  kExitOk = 0,
  kExitFailure = 1,           // the work failed (e.g. a solver failure)
  kExitUsage = 2,             // bad command line
  kExitBadInput = 3,          // unreadable or malformed input file
  kExitInsufficientData = 4,  // well-formed input with too little evidence for a result (InsufficientData)
  kExitCancelled = 130        // interrupted (Ctrl-C)
};

class Args {
 public:
  // flags: names of options that take no value (without "--"); "help" (and
  // "-h") always is one.
  Args(const std::vector<std::string>& argv, std::set<std::string> flags);

  // An option given last without its value (and not a flag) counts as
  // given: Has() is true and reading it throws "needs a value"; AllowOnly()
  // names it as unknown first when it is not allowed.
  bool Has(const std::string& name) const { return values_.count(name) > 0 || missing_value_.count(name) > 0; }
  std::string Get(const std::string& name, const std::string& fallback = "") const;
  // Throws UsageError when the value is not a number.
  double GetDouble(const std::string& name, double fallback) const;
  long long GetInt(const std::string& name, long long fallback) const;
  std::optional<std::string> Optional(const std::string& name) const;
  const std::vector<std::string>& positionals() const { return positionals_; }
  // Throws UsageError naming the first option not in allowed.
  void AllowOnly(const std::set<std::string>& allowed) const;

 private:
  void RefuseMissingValue(const std::string& name) const;

  std::map<std::string, std::string> values_;
  std::set<std::string> missing_value_;
  std::vector<std::string> positionals_;
};

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Refuses an output location the results could not be written to (see
// OutputLocationProblem in base/file_io.h) before any work: UsageError,
// exit 2, "--out PATH: why".
void CheckOutputFolder(const std::string& path, const char* option = "--out");
void CheckOutputFile(const std::string& path, const char* option = "--out");

}  // namespace hull::cli
