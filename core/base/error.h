// One exception hierarchy for bad input and refused options (F3D's
// load_failure_exception, COLMAP's Check()). Errors name the file, line,
// column and field at fault and what was expected; expected outcomes such as
// a cancelled job are status values, not exceptions.
#pragma once

#include <stdexcept>
#include <string>

namespace hull {

// Where in an input file something went wrong. line and column are 1-based;
// 0 means "not applicable" (e.g. a binary file or the file as a whole).
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
  std::string field;  // column name, JSON key path or record name

  std::string ToString() const;  // "file:line:column (field)"
};

// Malformed or inconsistent input: a survey bundle, a mesh, a project file.
class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation where, const std::string& message);
  const SourceLocation& where() const { return where_; }
  // The message without the location prefix.
  const std::string& detail() const { return detail_; }

 private:
  SourceLocation where_;
  std::string detail_;
};

// Options that fail their Check(): names the field and why.
class OptionError : public std::invalid_argument {
 public:
  OptionError(const std::string& field, const std::string& why);
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

// The inputs are well-formed but hold too little evidence for a result:
// images that gave no features, stereo pairs that match nowhere, a survey
// whose cameras measured none of the model, acoustic images with no
// detections. The run stops instead of reporting a result from nothing (a
// "clean hull" nobody saw): hullinspect-cli exits with status 4. `stage`
// names the step that had too little ("front end", "mapping", "sonar
// images"); `where` the file or folder the evidence came from (may be empty).
class InsufficientData : public std::runtime_error {
 public:
  InsufficientData(std::string stage, const std::string& what, std::string where = "");
  const std::string& stage() const { return stage_; }
  const std::string& where() const { return where_; }
  const std::string& detail() const { return detail_; }

 private:
  std::string stage_;
  std::string where_;
  std::string detail_;
};

// A job stopped because the user asked it to (thrown only across internal
// layers; public job functions turn it into a Status).
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled by the user") {}
};

// Collects the problems found by a validator instead of stopping at the first.
enum class Severity { kError, kWarning };
struct Problem {
  SourceLocation where;
  std::string message;
  Severity severity = Severity::kError;
  std::string ToString() const;
};

}  // namespace hull
