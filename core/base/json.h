// A small JSON document model that remembers where each value was in its
// file, so that a wrong field is reported with file, line and column.
// nlohmann::json parses the text (its SAX interface builds this model; its
// 3.11 in Debian 12 keeps no positions of values, so json.cc finds them) and
// escapes strings on writing; numbers are written in their shortest
// round-trip form, as in the CSV files.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/error.h"

namespace hull {

class Json {
 public:
  enum class Type { kNull, kBool, kNumber, kString, kArray, kObject };

  Json() = default;
  Json(std::nullptr_t) {}
  Json(bool b) : type_(Type::kBool), bool_(b) {}
  Json(double v) : type_(Type::kNumber), number_(v) {}
  Json(int v) : type_(Type::kNumber), number_(v), integer_(true) {}
  Json(std::int64_t v) : type_(Type::kNumber), number_(static_cast<double>(v)), integer_(true) {}
  Json(const char* s) : type_(Type::kString), string_(s) {}
  Json(std::string s) : type_(Type::kString), string_(std::move(s)) {}
  static Json Array() {
    Json j;
    j.type_ = Type::kArray;
    return j;
  }
  static Json Object() {
    Json j;
    j.type_ = Type::kObject;
    return j;
  }
  template <typename Container>
  static Json ArrayOf(const Container& values) {
    Json j = Array();
    for (const auto& v : values) j.Push(Json(v));
    return j;
  }

  Type type() const { return type_; }
  bool is_null() const { return type_ == Type::kNull; }
  bool is_bool() const { return type_ == Type::kBool; }
  bool is_number() const { return type_ == Type::kNumber; }
  bool is_integer() const { return type_ == Type::kNumber && integer_; }
  bool is_string() const { return type_ == Type::kString; }
  bool is_array() const { return type_ == Type::kArray; }
  bool is_object() const { return type_ == Type::kObject; }
  static const char* TypeName(Type t);

  bool as_bool() const { return bool_; }
  double as_number() const { return number_; }
  const std::string& as_string() const { return string_; }
  const std::vector<Json>& items() const { return items_; }
  const std::vector<std::pair<std::string, Json>>& members() const { return members_; }

  // Object access: nullptr when absent (or not an object).
  const Json* Get(std::string_view key) const;
  // Object building: sets (replaces) a member, keeps insertion order.
  Json& Set(const std::string& key, Json value);
  Json& Push(Json value);

  int line() const { return line_; }
  int column() const { return column_; }

  // Parses text; throws InputError with file, line and column on bad syntax.
  static Json Parse(std::string_view text, const std::string& file);
  // Pretty printed with two-space indents; short numeric arrays on one line.
  std::string Dump(int indent = 2) const;

 private:
  friend class JsonParser;
  void DumpTo(std::string& out, int indent, int depth) const;

  Type type_ = Type::kNull;
  bool bool_ = false;
  double number_ = 0;
  bool integer_ = false;
  std::string string_;
  std::vector<Json> items_;
  std::vector<std::pair<std::string, Json>> members_;
  int line_ = 0, column_ = 0;
};

// Reads typed fields from a parsed JSON object and reports every problem with
// the file, line, column and dotted key path ("camera.top.fx").
class JsonReader {
 public:
  JsonReader(const Json& value, std::string file, std::string path = "");
  const Json& value() const { return value_; }
  const std::string& file() const { return file_; }
  std::string PathOf(std::string_view key) const;
  bool Has(std::string_view key) const { return value_.Get(key) != nullptr; }

  JsonReader Object(std::string_view key) const;  // required object member
  std::optional<JsonReader> OptionalObject(std::string_view key) const;
  double Number(std::string_view key) const;                     // required finite number
  double NumberOr(std::string_view key, double fallback) const;  // optional
  std::int64_t Integer(std::string_view key) const;
  std::string String(std::string_view key) const;
  std::optional<std::string> OptionalString(std::string_view key) const;
  // A numeric array of exactly n finite values (n < 0: any length).
  std::vector<double> Numbers(std::string_view key, int n) const;
  std::optional<std::vector<double>> OptionalNumbers(std::string_view key, int n) const;
  const Json& Required(std::string_view key) const;

  [[noreturn]] void Fail(const Json& at, std::string_view key, const std::string& message) const;
  SourceLocation Where(const Json& at, std::string_view key) const;

 private:
  std::vector<double> NumbersOf(const Json& v, std::string_view key, int n) const;
  const Json& value_;
  std::string file_;
  std::string path_;
};

}  // namespace hull
