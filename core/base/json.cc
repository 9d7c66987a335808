#include "base/json.h"

#include <cmath>
#include <cstring>

#include "base/csv.h"

namespace hull {

const char* Json::TypeName(Type t) {
  switch (t) {
    case Type::kNull:
      return "null";
    case Type::kBool:
      return "a boolean";
    case Type::kNumber:
      return "a number";
    case Type::kString:
      return "a string";
    case Type::kArray:
      return "an array";
    case Type::kObject:
      return "an object";
  }
  return "?";
}

const Json* Json::Get(std::string_view key) const {
  if (type_ != Type::kObject) return nullptr;
  for (const auto& [k, v] : members_) {
    if (k == key) return &v;
  }
  return nullptr;
}

Json& Json::Set(const std::string& key, Json value) {
  type_ = Type::kObject;
  for (auto& [k, v] : members_) {
    if (k == key) {
      v = std::move(value);
      return v;
    }
  }
  members_.emplace_back(key, std::move(value));
  return members_.back().second;
}

Json& Json::Push(Json value) {
  type_ = Type::kArray;
  items_.push_back(std::move(value));
  return items_.back();
}

// ---------------------------------------------------------------------------
class JsonParser {
 public:
  JsonParser(std::string_view text, const std::string& file) : s_(text), file_(file) {}

  Json ParseDocument() {
    SkipSpace();
    Json v = ParseValue(0);
    SkipSpace();
    if (p_ < s_.size()) Fail("unexpected text after the JSON document");
    return v;
  }

 private:
  [[noreturn]] void Fail(const std::string& what) const {
    throw InputError({file_, line_, static_cast<int>(p_ - line_start_) + 1, ""}, what);
  }
  void SkipSpace() {
    while (p_ < s_.size()) {
      char c = s_[p_];
      if (c == '\n') {
        ++line_;
        line_start_ = p_ + 1;
      } else if (c != ' ' && c != '\t' && c != '\r') {
        break;
      }
      ++p_;
    }
  }
  void Mark(Json& v) const {
    v.line_ = line_;
    v.column_ = static_cast<int>(p_ - line_start_) + 1;
  }
  bool Consume(std::string_view word) {
    if (s_.substr(p_, word.size()) == word) {
      p_ += word.size();
      return true;
    }
    return false;
  }

  Json ParseValue(int depth) {
    if (depth > 200) Fail("JSON nested too deeply");
    if (p_ >= s_.size()) Fail("unexpected end of the file; expected a value");
    Json v;
    Mark(v);
    char c = s_[p_];
    if (c == '{') {
      v.type_ = Json::Type::kObject;
      ++p_;
      SkipSpace();
      if (p_ < s_.size() && s_[p_] == '}') {
        ++p_;
        return v;
      }
      while (true) {
        SkipSpace();
        if (p_ >= s_.size() || s_[p_] != '"') Fail("expected a quoted key");
        std::string key = ParseString();
        for (const auto& m : v.members_) {
          if (m.first == key) Fail("duplicate key \"" + key + "\"");
        }
        SkipSpace();
        if (p_ >= s_.size() || s_[p_] != ':') Fail("expected ':' after the key \"" + key + "\"");
        ++p_;
        SkipSpace();
        v.members_.emplace_back(std::move(key), ParseValue(depth + 1));
        SkipSpace();
        if (p_ < s_.size() && s_[p_] == ',') {
          ++p_;
          continue;
        }
        if (p_ < s_.size() && s_[p_] == '}') {
          ++p_;
          return v;
        }
        Fail("expected ',' or '}' in an object");
      }
    }
    if (c == '[') {
      v.type_ = Json::Type::kArray;
      ++p_;
      SkipSpace();
      if (p_ < s_.size() && s_[p_] == ']') {
        ++p_;
        return v;
      }
      while (true) {
        SkipSpace();
        v.items_.push_back(ParseValue(depth + 1));
        SkipSpace();
        if (p_ < s_.size() && s_[p_] == ',') {
          ++p_;
          continue;
        }
        if (p_ < s_.size() && s_[p_] == ']') {
          ++p_;
          return v;
        }
        Fail("expected ',' or ']' in an array");
      }
    }
    if (c == '"') {
      v.type_ = Json::Type::kString;
      v.string_ = ParseString();
      return v;
    }
    if (Consume("true")) {
      v.type_ = Json::Type::kBool;
      v.bool_ = true;
      return v;
    }
    if (Consume("false")) {
      v.type_ = Json::Type::kBool;
      return v;
    }
    if (Consume("null")) return v;
    if (c == '-' || (c >= '0' && c <= '9')) {
      std::size_t start = p_;
      bool integer = true;
      if (s_[p_] == '-') ++p_;
      while (p_ < s_.size()) {
        char d = s_[p_];
        if (d >= '0' && d <= '9') {
          ++p_;
        } else if (d == '.' || d == 'e' || d == 'E' || d == '+' || d == '-') {
          integer = false;
          ++p_;
        } else {
          break;
        }
      }
      double x = 0;
      if (!ParseFiniteDouble(s_.substr(start, p_ - start), x)) {
        p_ = start;
        Fail("malformed number");
      }
      v.type_ = Json::Type::kNumber;
      v.number_ = x;
      v.integer_ = integer;
      return v;
    }
    if (Consume("NaN") || Consume("Infinity") || Consume("-Infinity")) {
      p_ -= 3;
      Fail("NaN and Infinity are not JSON numbers");
    }
    Fail(std::string("unexpected character '") + c + "'; expected a JSON value");
  }

  static void AppendUtf8(std::string& out, unsigned cp) {
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xC0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xE0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }

  unsigned Hex4() {
    if (p_ + 4 > s_.size()) Fail("truncated \\u escape");
    unsigned cp = 0;
    for (int i = 0; i < 4; ++i) {
      char h = s_[p_++];
      cp <<= 4;
      if (h >= '0' && h <= '9')
        cp |= static_cast<unsigned>(h - '0');
      else if (h >= 'a' && h <= 'f')
        cp |= static_cast<unsigned>(h - 'a' + 10);
      else if (h >= 'A' && h <= 'F')
        cp |= static_cast<unsigned>(h - 'A' + 10);
      else
        Fail("bad hex digit in a \\u escape");
    }
    return cp;
  }

  std::string ParseString() {
    ++p_;  // opening quote
    std::string out;
    while (true) {
      if (p_ >= s_.size()) Fail("string is not closed before the end of the file");
      char c = s_[p_];
      if (c == '"') {
        ++p_;
        return out;
      }
      if (c == '\n') Fail("line break inside a string");
      if (c == '\\') {
        ++p_;
        if (p_ >= s_.size()) Fail("truncated escape");
        char e = s_[p_++];
        switch (e) {
          case '"':
            out += '"';
            break;
          case '\\':
            out += '\\';
            break;
          case '/':
            out += '/';
            break;
          case 'b':
            out += '\b';
            break;
          case 'f':
            out += '\f';
            break;
          case 'n':
            out += '\n';
            break;
          case 'r':
            out += '\r';
            break;
          case 't':
            out += '\t';
            break;
          case 'u': {
            unsigned cp = Hex4();
            if (cp >= 0xD800 && cp < 0xDC00 && Consume("\\u")) {
              unsigned lo = Hex4();
              cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
            }
            AppendUtf8(out, cp);
            break;
          }
          default:
            --p_;
            Fail(std::string("unknown escape \\") + e);
        }
        continue;
      }
      out += c;
      ++p_;
    }
  }

  std::string_view s_;
  const std::string& file_;
  std::size_t p_ = 0;
  int line_ = 1;
  std::size_t line_start_ = 0;
};

Json Json::Parse(std::string_view text, const std::string& file) {
  if (text.size() >= 3 && static_cast<unsigned char>(text[0]) == 0xEF) text.remove_prefix(3);
  return JsonParser(text, file).ParseDocument();
}

namespace {
void DumpString(std::string& out, const std::string& s) {
  out += '"';
  for (char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof(buf), "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  out += '"';
}
}  // namespace

void Json::DumpTo(std::string& out, int indent, int depth) const {
  auto newline = [&](int d) {
    out += '\n';
    out.append(static_cast<std::size_t>(indent * d), ' ');
  };
  switch (type_) {
    case Type::kNull:
      out += "null";
      break;
    case Type::kBool:
      out += bool_ ? "true" : "false";
      break;
    case Type::kNumber:
      if (integer_ && std::fabs(number_) < 9e15) {
        out += std::to_string(static_cast<std::int64_t>(number_));
      } else {
        AppendDouble(out, number_);
      }
      break;
    case Type::kString:
      DumpString(out, string_);
      break;
    case Type::kArray: {
      bool flat = true;
      for (const auto& it : items_) flat = flat && (it.is_number() || it.is_bool() || it.is_null());
      out += '[';
      for (std::size_t i = 0; i < items_.size(); ++i) {
        if (i) out += flat ? ", " : ",";
        if (!flat) newline(depth + 1);
        items_[i].DumpTo(out, indent, depth + 1);
      }
      if (!flat && !items_.empty()) newline(depth);
      out += ']';
      break;
    }
    case Type::kObject: {
      out += '{';
      for (std::size_t i = 0; i < members_.size(); ++i) {
        if (i) out += ',';
        newline(depth + 1);
        DumpString(out, members_[i].first);
        out += ": ";
        members_[i].second.DumpTo(out, indent, depth + 1);
      }
      if (!members_.empty()) newline(depth);
      out += '}';
      break;
    }
  }
}

std::string Json::Dump(int indent) const {
  std::string out;
  DumpTo(out, indent, 0);
  out += '\n';
  return out;
}

// ---------------------------------------------------------------------------
JsonReader::JsonReader(const Json& value, std::string file, std::string path)
    : value_(value), file_(std::move(file)), path_(std::move(path)) {
  if (!value_.is_object()) {
    throw InputError({file_, value_.line(), value_.column(), path_.empty() ? "(document)" : path_},
                     std::string("expected an object, got ") + Json::TypeName(value_.type()));
  }
}

std::string JsonReader::PathOf(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

SourceLocation JsonReader::Where(const Json& at, std::string_view key) const {
  return {file_, at.line(), at.column(), PathOf(key)};
}

void JsonReader::Fail(const Json& at, std::string_view key, const std::string& message) const {
  throw InputError(Where(at, key), message);
}

const Json& JsonReader::Required(std::string_view key) const {
  const Json* v = value_.Get(key);
  if (!v) Fail(value_, key, "required key \"" + std::string(key) + "\" is missing");
  return *v;
}

JsonReader JsonReader::Object(std::string_view key) const {
  const Json& v = Required(key);
  if (!v.is_object()) Fail(v, key, std::string("expected an object, got ") + Json::TypeName(v.type()));
  return JsonReader(v, file_, PathOf(key));
}

std::optional<JsonReader> JsonReader::OptionalObject(std::string_view key) const {
  if (!Has(key)) return std::nullopt;
  return Object(key);
}

double JsonReader::Number(std::string_view key) const {
  const Json& v = Required(key);
  if (!v.is_number()) Fail(v, key, std::string("expected a number, got ") + Json::TypeName(v.type()));
  return v.as_number();
}

double JsonReader::NumberOr(std::string_view key, double fallback) const { return Has(key) ? Number(key) : fallback; }

std::int64_t JsonReader::Integer(std::string_view key) const {
  const Json& v = Required(key);
  if (!v.is_integer()) Fail(v, key, std::string("expected an integer, got ") + Json::TypeName(v.type()));
  return static_cast<std::int64_t>(v.as_number());
}

std::string JsonReader::String(std::string_view key) const {
  const Json& v = Required(key);
  if (!v.is_string()) Fail(v, key, std::string("expected a string, got ") + Json::TypeName(v.type()));
  return v.as_string();
}

std::optional<std::string> JsonReader::OptionalString(std::string_view key) const {
  if (!Has(key)) return std::nullopt;
  return String(key);
}

std::vector<double> JsonReader::NumbersOf(const Json& v, std::string_view key, int n) const {
  if (!v.is_array()) Fail(v, key, std::string("expected an array of numbers, got ") + Json::TypeName(v.type()));
  if (n >= 0 && v.items().size() != static_cast<std::size_t>(n)) {
    Fail(v, key, "expected " + std::to_string(n) + " numbers, got " + std::to_string(v.items().size()));
  }
  std::vector<double> out;
  out.reserve(v.items().size());
  for (const Json& it : v.items()) {
    if (!it.is_number()) Fail(it, key, std::string("expected a number, got ") + Json::TypeName(it.type()));
    out.push_back(it.as_number());
  }
  return out;
}

std::vector<double> JsonReader::Numbers(std::string_view key, int n) const { return NumbersOf(Required(key), key, n); }

std::optional<std::vector<double>> JsonReader::OptionalNumbers(std::string_view key, int n) const {
  const Json* v = value_.Get(key);
  if (!v || v->is_null()) return std::nullopt;
  return NumbersOf(*v, key, n);
}

}  // namespace hull
