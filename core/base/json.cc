#include "base/json.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <iterator>

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
// Parsing: nlohmann::json's SAX parser (lexing, grammar, escapes, UTF-8
// validation) builds our document. nlohmann 3.11 reports no positions of
// values, only the byte offset of a syntax error, so the parser reads the
// text through an iterator that publishes how far the lexer has read; each
// value's first byte is found from there (its token has just ended) and
// turned into line and column.
namespace {

using NJson = nlohmann::json;

// Deeper documents are refused: the document model, its writer and its
// destructor recurse (hostile input: tests/fuzz, json harness).
constexpr int kMaxDepth = 200;

class TrackingIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  TrackingIterator(const char* p, const char** read) : p_(p), read_(read) {}
  reference operator*() const { return *p_; }
  TrackingIterator& operator++() {
    *read_ = ++p_;
    return *this;
  }
  TrackingIterator operator++(int) {
    TrackingIterator before = *this;
    ++*this;
    return before;
  }
  bool operator==(const TrackingIterator& o) const { return p_ == o.p_; }
  bool operator!=(const TrackingIterator& o) const { return p_ != o.p_; }

 private:
  const char* p_;
  const char** read_;
};

bool IsNumberChar(char c) { return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == 'e' || c == 'E'; }

}  // namespace

class JsonParser {
 public:
  JsonParser(std::string_view text, const std::string& file) : s_(text), file_(file), read_(text.data()) {}

  Json ParseDocument() {
    const TrackingIterator first(s_.data(), &read_), last(s_.data() + s_.size(), &read_);
    NJson::sax_parse(first, last, this);  // errors throw InputError from the callbacks
    return std::move(root_);
  }

  // ---- nlohmann's SAX interface ----
  bool null() {
    Place(Json(), Read() - 4);
    return true;
  }
  bool boolean(bool b) {
    Place(Json(b), Read() - (b ? 4 : 5));
    return true;
  }
  bool number_integer(NJson::number_integer_t v) {
    Place(Json(static_cast<std::int64_t>(v)), NumberStart());
    return true;
  }
  bool number_unsigned(NJson::number_unsigned_t v) {
    Json j(static_cast<double>(v));
    j.integer_ = true;
    Place(std::move(j), NumberStart());
    return true;
  }
  bool number_float(NJson::number_float_t v, const NJson::string_t& /*text*/) {
    Place(Json(static_cast<double>(v)), NumberStart());  // finite: nlohmann refuses an overflow
    return true;
  }
  bool string(NJson::string_t& v) {
    Place(Json(std::move(v)), StringStart());
    return true;
  }
  bool binary(NJson::binary_t& /*v*/) { return true; }  // not produced by JSON text
  bool start_object(std::size_t /*elements*/) {
    Open(Json::Object());
    return true;
  }
  bool key(NJson::string_t& k) {
    const Json& object = *stack_.back();
    for (const auto& m : object.members_) {
      if (m.first == k) Fail(Read(), "duplicate key \"" + k + "\"");
    }
    key_ = std::move(k);
    return true;
  }
  bool end_object() { return Close(); }
  bool start_array(std::size_t /*elements*/) {
    Open(Json::Array());
    return true;
  }
  bool end_array() { return Close(); }
  bool parse_error(std::size_t position, const std::string& /*last_token*/, const nlohmann::detail::exception& e) {
    // `position` counts the bytes read. The lexer stops at the byte that
    // broke a token ("; last read: " in the message); a token that is whole
    // but out of place (or a number out of range) is pointed at its start.
    const std::string what = e.what();
    std::size_t at = position > 0 ? position - 1 : 0;
    if (what.find("; last read: ") == std::string::npos) at = TokenStart(at);
    at = std::min(at, s_.size());
    Fail(at, Explain(at, e.id, what));
  }

 private:
  std::size_t Read() const { return static_cast<std::size_t>(read_ - s_.data()); }

  // A number's token has ended at the lexer's look-ahead (or the end of the text).
  std::size_t NumberStart() const {
    std::size_t p = Read();
    if (p > 0 && !IsNumberChar(s_[p - 1])) --p;
    while (p > 0 && IsNumberChar(s_[p - 1])) --p;
    return p;
  }
  // A string's token has ended at its closing quote.
  std::size_t StringStart() const { return OpeningQuote(Read() - 1); }
  // The opening quote of the string closed at `close`: the first quote before
  // it that is not escaped (preceded by an even number of '\').
  std::size_t OpeningQuote(std::size_t close) const {
    std::size_t q = close;
    while (q > 0) {
      --q;
      if (s_[q] != '"') continue;
      std::size_t slashes = 0;
      while (slashes < q && s_[q - 1 - slashes] == '\\') ++slashes;
      if (slashes % 2 == 0) return q;
    }
    return 0;
  }
  // The first byte of the whole token whose last byte is at `last` (a
  // string, a number, a literal or one structural character).
  std::size_t TokenStart(std::size_t last) const {
    if (last >= s_.size()) return s_.size();
    if (s_[last] == '"' && last > 0) return OpeningQuote(last);
    const auto word = [](char c) { return IsNumberChar(c) || (c >= 'a' && c <= 'z'); };
    if (!word(s_[last])) return last;
    while (last > 0 && word(s_[last - 1])) --last;
    return last;
  }

  Json& Place(Json v, std::size_t start) {
    const auto [line, column] = LineColumn(start);
    v.line_ = line;
    v.column_ = column;
    if (stack_.empty()) {
      root_ = std::move(v);
      return root_;
    }
    Json& parent = *stack_.back();
    if (parent.type_ == Json::Type::kArray) {
      parent.items_.push_back(std::move(v));
      return parent.items_.back();
    }
    parent.members_.emplace_back(std::move(key_), std::move(v));
    return parent.members_.back().second;
  }
  void Open(Json container) {
    const std::size_t start = Read() - 1;  // '{' or '['
    if (static_cast<int>(stack_.size()) >= kMaxDepth) Fail(start, "JSON nested too deeply");
    stack_.push_back(&Place(std::move(container), start));
  }
  bool Close() {
    stack_.pop_back();
    return true;
  }

  // nlohmann's message without its prefix ("[json.exception.parse_error.101]
  // parse error at line 1, column 7: "), led by what was expected there.
  std::string Explain(std::size_t at, int id, const std::string& what) const {
    const std::string_view rest = s_.substr(at);
    if (rest.rfind("NaN", 0) == 0 || rest.rfind("Infinity", 0) == 0 || rest.rfind("-Infinity", 0) == 0) {
      return "NaN and Infinity are not JSON numbers";
    }
    std::string why = what;
    if (why.rfind("[json.exception.", 0) == 0 && why.find("] ") != std::string::npos) {
      why = why.substr(why.find("] ") + 2);
    }
    if (why.rfind("parse error", 0) == 0 && why.find(": ") != std::string::npos) why = why.substr(why.find(": ") + 2);
    const auto in = [&](const char* context) { return why.find(context) != std::string::npos; };
    if (id == 406) return "number out of range (" + why + ")";
    if (in("while parsing object key ")) return "expected a quoted key (" + why + ")";
    if (in("while parsing object separator ")) return "expected ':' after the key \"" + key_ + "\" (" + why + ")";
    if (in("while parsing object ")) return "expected ',' or '}' in an object (" + why + ")";
    if (in("while parsing array ")) return "expected ',' or ']' in an array (" + why + ")";
    if (in("expected end of input")) return "unexpected text after the JSON document (" + why + ")";
    return why;
  }

  [[noreturn]] void Fail(std::size_t at, const std::string& message) {
    const auto [line, column] = LineColumn(at);
    throw InputError({file_, line, column, ""}, message);
  }

  // 1-based line and column of byte `at`; offsets mostly increase, so the
  // line count carries on from the previous call.
  std::pair<int, int> LineColumn(std::size_t at) {
    if (at < scanned_) {
      scanned_ = 0;
      line_ = 1;
      line_start_ = 0;
    }
    while (scanned_ < at) {
      const void* nl = std::memchr(s_.data() + scanned_, '\n', at - scanned_);
      if (!nl) {
        scanned_ = at;
        break;
      }
      scanned_ = static_cast<std::size_t>(static_cast<const char*>(nl) - s_.data()) + 1;
      line_start_ = scanned_;
      ++line_;
    }
    return {line_, static_cast<int>(at - line_start_) + 1};
  }

  std::string_view s_;
  const std::string& file_;
  const char* read_;  // one past the last byte the lexer read
  Json root_;
  std::vector<Json*> stack_;  // the open arrays and objects
  std::string key_;           // the key of the member whose value comes next
  std::size_t scanned_ = 0;
  int line_ = 1;
  std::size_t line_start_ = 0;
};

Json Json::Parse(std::string_view text, const std::string& file) {
  if (text.size() >= 3 && static_cast<unsigned char>(text[0]) == 0xEF) text.remove_prefix(3);
  return JsonParser(text, file).ParseDocument();
}

// ---------------------------------------------------------------------------
// Writing: our layout (two-space indents, numeric arrays on one line),
// numbers in their shortest round-trip form as the CSV files print them
// (std::to_chars, base/csv.h), strings escaped by nlohmann (invalid UTF-8
// becomes U+FFFD, so whatever is written reads back).
namespace {
void DumpString(std::string& out, const std::string& s) {
  out += NJson(s).dump(-1, ' ', false, NJson::error_handler_t::replace);
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
