// A streaming reader and a writer for the contract's CSV dialect (RFC 4180:
// comma separated, a header row, '.' decimal mark, UTF-8, "\n" or "\r\n",
// quoted fields with "" escapes). Columns are found by header name; every
// error names the file, line, column and field. Fast enough for millions of
// rows: no per-field allocation unless a field is quoted with escapes.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.h"

namespace hull {

class CsvReader {
 public:
  // text must outlive the reader; file is the name used in error messages.
  // Reads the header row (throws InputError when it is missing, empty or has
  // duplicate names).
  CsvReader(std::string_view text, std::string file);

  const std::vector<std::string>& header() const { return header_; }
  const std::string& file() const { return file_; }
  // Index of a header column, or -1.
  int Find(std::string_view name) const;
  // Index of a required header column; throws naming the header line.
  int Require(std::string_view name) const;

  // Advances to the next record; false at the end of the file. Throws when a
  // record has a different number of fields than the header or a quoted
  // field is not closed. Blank lines are skipped.
  bool Next();
  int line() const { return line_; }
  std::size_t size() const { return fields_.size(); }

  // Raw field text (whitespace around it trimmed); "" when col < 0.
  std::string_view Field(int col) const;
  bool Empty(int col) const { return col < 0 || Field(col).empty(); }
  // Typed access: finite double / integer; throws on an empty field, text,
  // nan or inf, naming file, line, column and field.
  double Double(int col) const;
  std::int64_t Int(int col) const;
  // As above, but an empty field (or an absent column, col < 0) is nullopt.
  std::optional<double> OptionalDouble(int col) const;
  std::optional<std::int64_t> OptionalInt(int col) const;

  SourceLocation Where(int col) const;
  [[noreturn]] void Fail(int col, const std::string& message) const;

 private:
  struct FieldRef {
    std::string_view text;
    int column;  // 1-based character column of the field start
  };
  bool ParseRecord(std::vector<FieldRef>& out, int& record_line);

  std::string_view text_;
  std::string file_;
  std::size_t pos_ = 0;
  int next_line_ = 1;
  int line_ = 0;
  std::vector<std::string> header_;
  std::vector<FieldRef> fields_;
  std::deque<std::string> unescaped_;  // fields with "" escapes (deque: stable addresses)
};

// Parses a finite double / integer in the contract's dialect (optional sign,
// no surrounding text). Returns false on failure.
bool ParseFiniteDouble(std::string_view s, double& out);
bool ParseInt64(std::string_view s, std::int64_t& out);

// Appends a double in the shortest form that reads back bit-identical.
void AppendDouble(std::string& out, double v);
std::string FormatDouble(double v);

// Builds CSV text row by row; fields that need it are quoted.
class CsvWriter {
 public:
  explicit CsvWriter(const std::vector<std::string>& header);
  CsvWriter& Add(double v);
  CsvWriter& Add(std::int64_t v);
  CsvWriter& Add(int v) { return Add(static_cast<std::int64_t>(v)); }
  CsvWriter& Add(std::string_view text);
  CsvWriter& AddOptional(const std::optional<double>& v);
  CsvWriter& AddEmpty();
  void EndRow();
  const std::string& text() const { return text_; }
  std::string&& Take() { return std::move(text_); }

 private:
  void Separator();
  std::string text_;
  bool row_start_ = true;
};

}  // namespace hull
