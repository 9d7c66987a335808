#include "cli/args.h"

#include <cstdint>
#include <stdexcept>

#include "base/csv.h"
#include "base/file_checks.h"
#include "base/file_io.h"

namespace hull::cli {

Args::Args(const std::vector<std::string>& argv, std::set<std::string> flags) {
  flags.insert("help");  // every command has --help (and -h)
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a.size() > 2 && a[0] == '-' && a[1] == '-') {
      std::string name = a.substr(2);
      const auto eq = name.find('=');
      if (eq != std::string::npos) {
        values_[name.substr(0, eq)] = name.substr(eq + 1);
      } else if (flags.count(name)) {
        values_[name] = "1";
      } else {
        if (i + 1 >= argv.size()) {
          missing_value_.insert(name);  // refused later: as unknown when it is, else as lacking its value
        } else {
          values_[name] = argv[++i];
        }
      }
    } else if (a == "-h") {
      values_["help"] = "1";
    } else {
      positionals_.push_back(a);
    }
  }
}

void Args::RefuseMissingValue(const std::string& name) const {
  if (missing_value_.count(name)) throw UsageError("option --" + name + " needs a value");
}

std::string Args::Get(const std::string& name, const std::string& fallback) const {
  RefuseMissingValue(name);
  auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second;
}

std::optional<std::string> Args::Optional(const std::string& name) const {
  RefuseMissingValue(name);
  auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

double Args::GetDouble(const std::string& name, double fallback) const {
  RefuseMissingValue(name);
  auto it = values_.find(name);
  if (it == values_.end()) return fallback;
  double v = 0;
  if (!ParseFiniteDouble(it->second, v)) {
    throw UsageError("option --" + name + " expects a number, got '" + it->second + "'");
  }
  return v;
}

static long long GetIntImpl(const std::string& name, const std::string& text) {
  std::int64_t v = 0;
  if (!ParseInt64(text, v)) throw UsageError("option --" + name + " expects an integer, got '" + text + "'");
  return v;
}

long long Args::GetInt(const std::string& name, long long fallback) const {
  RefuseMissingValue(name);
  auto it = values_.find(name);
  return it == values_.end() ? fallback : GetIntImpl(name, it->second);
}

void Args::AllowOnly(const std::set<std::string>& allowed) const {
  for (const auto& [k, v] : values_) {
    if (k != "help" && !allowed.count(k)) throw UsageError("unknown option --" + k);
  }
  for (const std::string& k : missing_value_) {
    if (!allowed.count(k)) throw UsageError("unknown option --" + k);
  }
  if (!missing_value_.empty()) RefuseMissingValue(*missing_value_.begin());
}

void CheckOutputFolder(const std::string& path, const char* option) {
  const std::string why = OutputLocationProblem(path, OutputKind::kFolder);
  if (!why.empty()) throw UsageError(std::string(option) + " " + path + ": " + why);
}

void CheckOutputFile(const std::string& path, const char* option) {
  const std::string why = OutputLocationProblem(path, OutputKind::kFile);
  if (!why.empty()) throw UsageError(std::string(option) + " " + path + ": " + why);
}

}  // namespace hull::cli
