#include "base/csv.h"

#include <charconv>
#include <cmath>
#include <unordered_set>

namespace hull {
namespace {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::string Quote(std::string_view s) {
  std::string out = "'";
  for (char c : s.substr(0, 40)) out += c;
  if (s.size() > 40) out += "...";
  return out + "'";
}

}  // namespace

bool ParseFiniteDouble(std::string_view s, double& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  // from_chars accepts "inf" and "nan"; the contract does not.
  const char c0 = s.front() == '-' && s.size() > 1 ? s[1] : s.front();
  if (!((c0 >= '0' && c0 <= '9') || c0 == '.')) return false;
  const char* end = s.data() + s.size();
  auto [p, ec] = std::from_chars(s.data(), end, out, std::chars_format::general);
  return ec == std::errc() && p == end && std::isfinite(out);
}

bool ParseInt64(std::string_view s, std::int64_t& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const char* end = s.data() + s.size();
  auto [p, ec] = std::from_chars(s.data(), end, out);
  return ec == std::errc() && p == end;
}

void AppendDouble(std::string& out, double v) {
  char buf[32];
  auto [p, ec] = std::to_chars(buf, buf + sizeof(buf), v);
  (void)ec;
  out.append(buf, p);
}

std::string FormatDouble(double v) {
  std::string s;
  AppendDouble(s, v);
  return s;
}

CsvReader::CsvReader(std::string_view text, std::string file) : text_(text), file_(std::move(file)) {
  if (text_.size() >= 3 && static_cast<unsigned char>(text_[0]) == 0xEF &&
      static_cast<unsigned char>(text_[1]) == 0xBB && static_cast<unsigned char>(text_[2]) == 0xBF) {
    pos_ = 3;  // UTF-8 byte order mark
  }
  std::vector<FieldRef> head;
  int head_line = 0;
  if (!ParseRecord(head, head_line)) {
    throw InputError({file_, 1, 1, "header"}, "the file is empty; expected a header row");
  }
  std::unordered_set<std::string> seen;
  for (const FieldRef& f : head) {
    std::string name(Trim(f.text));
    if (name.empty()) throw InputError({file_, head_line, f.column, "header"}, "empty column name in the header");
    if (!seen.insert(name).second) {
      throw InputError({file_, head_line, f.column, name}, "column '" + name + "' appears twice in the header");
    }
    header_.push_back(std::move(name));
  }
}

int CsvReader::Find(std::string_view name) const {
  for (std::size_t i = 0; i < header_.size(); ++i) {
    if (header_[i] == name) return static_cast<int>(i);
  }
  return -1;
}

int CsvReader::Require(std::string_view name) const {
  int i = Find(name);
  if (i < 0) {
    std::string have;
    for (const auto& h : header_) have += (have.empty() ? "" : ",") + h;
    throw InputError({file_, 1, 1, std::string(name)},
                     "the header lacks the required column '" + std::string(name) + "' (header: " + have + ")");
  }
  return i;
}

bool CsvReader::ParseRecord(std::vector<FieldRef>& out, int& record_line) {
  out.clear();
  // Skip blank lines.
  while (pos_ < text_.size() && (text_[pos_] == '\n' || text_[pos_] == '\r')) {
    if (text_[pos_] == '\n') ++next_line_;
    ++pos_;
  }
  if (pos_ >= text_.size()) return false;
  record_line = next_line_;
  std::size_t line_start = pos_;
  const std::size_t n = text_.size();
  while (true) {
    const int column = static_cast<int>(pos_ - line_start) + 1;
    if (pos_ < n && text_[pos_] == '"') {
      // Quoted field.
      std::size_t start = ++pos_;
      bool escaped = false;
      while (true) {
        if (pos_ >= n) {
          throw InputError({file_, record_line, column, out.size() < header_.size() ? header_[out.size()] : ""},
                           "quoted field is not closed before the end of the file");
        }
        char c = text_[pos_];
        if (c == '"') {
          if (pos_ + 1 < n && text_[pos_ + 1] == '"') {
            escaped = true;
            pos_ += 2;
            continue;
          }
          break;
        }
        if (c == '\n') {
          ++next_line_;
          line_start = pos_ + 1;
        }
        ++pos_;
      }
      std::string_view raw = text_.substr(start, pos_ - start);
      ++pos_;  // closing quote
      if (escaped) {
        std::string s;
        for (std::size_t i = 0; i < raw.size(); ++i) {
          s += raw[i];
          if (raw[i] == '"') ++i;
        }
        unescaped_.push_back(std::move(s));
        raw = unescaped_.back();
      }
      out.push_back({raw, column});
      if (pos_ < n && text_[pos_] != ',' && text_[pos_] != '\n' && text_[pos_] != '\r') {
        throw InputError({file_, record_line, static_cast<int>(pos_ - line_start) + 1, ""},
                         "unexpected text after a closing quote; expected ',' or the end of the line");
      }
    } else {
      std::size_t start = pos_;
      while (pos_ < n && text_[pos_] != ',' && text_[pos_] != '\n' && text_[pos_] != '\r') ++pos_;
      out.push_back({Trim(text_.substr(start, pos_ - start)), column});
    }
    if (pos_ < n && text_[pos_] == ',') {
      ++pos_;
      continue;
    }
    // End of record.
    if (pos_ < n && text_[pos_] == '\r') ++pos_;
    if (pos_ < n && text_[pos_] == '\n') ++pos_;
    ++next_line_;
    return true;
  }
}

bool CsvReader::Next() {
  unescaped_.clear();
  if (!ParseRecord(fields_, line_)) return false;
  if (fields_.size() != header_.size()) {
    throw InputError(
        {file_, line_, fields_.empty() ? 1 : fields_.back().column, ""},
        "the line has " + std::to_string(fields_.size()) + " fields, the header has " + std::to_string(header_.size()));
  }
  return true;
}

std::string_view CsvReader::Field(int col) const {
  if (col < 0 || static_cast<std::size_t>(col) >= fields_.size()) return {};
  return fields_[static_cast<std::size_t>(col)].text;
}

SourceLocation CsvReader::Where(int col) const {
  SourceLocation w{file_, line_, 0, ""};
  if (col >= 0 && static_cast<std::size_t>(col) < fields_.size()) {
    w.column = fields_[static_cast<std::size_t>(col)].column;
    w.field = header_[static_cast<std::size_t>(col)];
  }
  return w;
}

void CsvReader::Fail(int col, const std::string& message) const { throw InputError(Where(col), message); }

double CsvReader::Double(int col) const {
  std::string_view s = Field(col);
  if (s.empty()) Fail(col, "empty field; expected a number");
  double v = 0;
  if (!ParseFiniteDouble(s, v)) Fail(col, "expected a finite number, got " + Quote(s));
  return v;
}

std::int64_t CsvReader::Int(int col) const {
  std::string_view s = Field(col);
  if (s.empty()) Fail(col, "empty field; expected an integer");
  std::int64_t v = 0;
  if (!ParseInt64(s, v)) Fail(col, "expected an integer, got " + Quote(s));
  return v;
}

std::optional<double> CsvReader::OptionalDouble(int col) const {
  if (Empty(col)) return std::nullopt;
  return Double(col);
}

std::optional<std::int64_t> CsvReader::OptionalInt(int col) const {
  if (Empty(col)) return std::nullopt;
  return Int(col);
}

CsvWriter::CsvWriter(const std::vector<std::string>& header) {
  for (const auto& h : header) Add(std::string_view(h));
  EndRow();
}

void CsvWriter::Separator() {
  if (!row_start_) text_ += ',';
  row_start_ = false;
}

CsvWriter& CsvWriter::Add(double v) {
  Separator();
  AppendDouble(text_, v);
  return *this;
}

CsvWriter& CsvWriter::Add(std::int64_t v) {
  Separator();
  text_ += std::to_string(v);
  return *this;
}

CsvWriter& CsvWriter::Add(std::string_view s) {
  Separator();
  if (s.find_first_of(",\"\n\r") == std::string_view::npos) {
    text_ += s;
    return *this;
  }
  text_ += '"';
  for (char c : s) {
    if (c == '"') text_ += '"';
    text_ += c;
  }
  text_ += '"';
  return *this;
}

CsvWriter& CsvWriter::AddOptional(const std::optional<double>& v) { return v ? Add(*v) : AddEmpty(); }

CsvWriter& CsvWriter::AddEmpty() {
  Separator();
  return *this;
}

void CsvWriter::EndRow() {
  text_ += '\n';
  row_start_ = true;
}

}  // namespace hull
