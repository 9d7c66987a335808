#include "base/error.h"

#include <utility>

namespace hull {

std::string SourceLocation::ToString() const {
  std::string s = file.empty() ? std::string("<input>") : file;
  if (line > 0) {
    s += ":" + std::to_string(line);
    if (column > 0) s += ":" + std::to_string(column);
  }
  if (!field.empty()) s += " (" + field + ")";
  return s;
}

InputError::InputError(SourceLocation where, const std::string& message)
    : std::runtime_error(where.ToString() + ": " + message), where_(std::move(where)), detail_(message) {}

OptionError::OptionError(const std::string& field, const std::string& why)
    : std::invalid_argument("option " + field + ": " + why), field_(field) {}

std::string Problem::ToString() const {
  return where.ToString() + (severity == Severity::kWarning ? ": warning: " : ": ") + message;
}

}  // namespace hull
