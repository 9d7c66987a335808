#include "base/json.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

namespace hull {
namespace {

TEST(Json, ParsesWithPositions) {
  const std::string text = "{\n  \"a\": 1,\n  \"b\": [1.5, -2e3, true, null],\n  \"c\": {\"d\": \"x\\u00e9\"}\n}\n";
  const Json j = Json::Parse(text, "t.json");
  ASSERT_TRUE(j.is_object());
  EXPECT_TRUE(j.Get("a")->is_integer());
  EXPECT_EQ(j.Get("a")->line(), 2);
  EXPECT_EQ(j.Get("a")->column(), 8);
  EXPECT_EQ(j.Get("b")->items()[1].as_number(), -2000.0);
  EXPECT_FALSE(j.Get("b")->items()[0].is_integer());
  EXPECT_EQ(j.Get("c")->Get("d")->as_string(), "x\xc3\xa9");
  EXPECT_EQ(j.Get("zz"), nullptr);
}

TEST(Json, SyntaxErrorsNameLineAndColumn) {
  struct Case {
    const char* text;
    int line, column;
  } cases[] = {{"{\n  \"a\": 1,\n}", 3, 1},      {"{\"a\" 1}", 1, 6},     {"[1, 2", 1, 6},
               {"{\"a\": NaN}", 1, 7},           {"{\"a\": 1} x", 1, 10}, {"{\"a\": 1, \"a\": 2}", 1, 13},
               {"{\"a\": \"unterminated", 1, 20}};
  for (const auto& c : cases) {
    try {
      Json::Parse(c.text, "bad.json");
      FAIL() << "accepted " << c.text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, "bad.json");
      EXPECT_EQ(e.where().line, c.line) << c.text << ": " << e.what();
      EXPECT_EQ(e.where().column, c.column) << c.text << ": " << e.what();
    }
  }
}

TEST(Json, ReaderReportsPathAndExpectation) {
  const Json j = Json::Parse("{\"cam\": {\"fx\": \"big\", \"v\": [1, 2]}}", "m.json");
  JsonReader r(j, "m.json");
  JsonReader cam = r.Object("cam");
  try {
    cam.Number("fx");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "cam.fx");
    EXPECT_NE(std::string(e.what()).find("expected a number"), std::string::npos);
  }
  EXPECT_THROW(cam.Numbers("v", 3), InputError);
  EXPECT_EQ(cam.Numbers("v", 2).size(), 2u);
  EXPECT_THROW(cam.Number("missing"), InputError);
  EXPECT_EQ(cam.NumberOr("missing", 7.0), 7.0);
}

TEST(Json, DumpRoundTrips) {
  Json root = Json::Object();
  root.Set("name", "a \"quoted\"\nname");
  root.Set("pi", 3.141592653589793);
  root.Set("n", 3);
  root.Set("v", Json::ArrayOf(std::vector<double>{0.1, 1e-17, -5.0}));
  Json nested = Json::Object();
  nested.Set("flag", true);
  root.Set("nested", nested);
  const Json back = Json::Parse(root.Dump(), "rt.json");
  EXPECT_EQ(back.Get("name")->as_string(), "a \"quoted\"\nname");
  EXPECT_EQ(back.Get("pi")->as_number(), 3.141592653589793);
  EXPECT_TRUE(back.Get("n")->is_integer());
  EXPECT_EQ(back.Get("v")->items()[1].as_number(), 1e-17);
  EXPECT_TRUE(back.Get("nested")->Get("flag")->as_bool());
}

// Byte offset of 1-based (line, column) in text.
std::size_t OffsetOf(const std::string& text, int line, int column) {
  std::size_t p = 0;
  for (int l = 1; l < line; ++l) p = text.find('\n', p) + 1;
  return p + static_cast<std::size_t>(column - 1);
}

// Every value's line and column point at its first character, whatever
// follows it (end of text, ',', ']', '}', blanks) and however its strings
// are escaped: the parser finds them from where nlohmann's lexer stopped.
void ExpectPositionsAtTokens(const Json& v, const std::string& text) {
  const std::size_t at = OffsetOf(text, v.line(), v.column());
  ASSERT_LT(at, text.size());
  const char c = text[at];
  switch (v.type()) {
    case Json::Type::kNull:
      EXPECT_EQ(text.compare(at, 4, "null"), 0) << at;
      break;
    case Json::Type::kBool:
      EXPECT_EQ(text.compare(at, v.as_bool() ? 4 : 5, v.as_bool() ? "true" : "false"), 0) << at;
      break;
    case Json::Type::kNumber: {
      std::size_t end = at;
      while (end < text.size() && std::strchr("0123456789+-.eE", text[end])) ++end;
      EXPECT_EQ(std::stod(text.substr(at, end - at)), v.as_number()) << at;
      EXPECT_TRUE(at == 0 || !std::strchr("0123456789+-.eE", text[at - 1])) << at;
      break;
    }
    case Json::Type::kString:
      EXPECT_EQ(c, '"') << at;
      break;
    case Json::Type::kArray:
      EXPECT_EQ(c, '[') << at;
      for (const Json& it : v.items()) ExpectPositionsAtTokens(it, text);
      break;
    case Json::Type::kObject:
      EXPECT_EQ(c, '{') << at;
      for (const auto& [k, m] : v.members()) ExpectPositionsAtTokens(m, text);
      break;
  }
}

TEST(Json, EveryValueKnowsWhereItStarts) {
  const std::string texts[] = {
      "{\"s\": \"a\\\"b\", \"t\": \"\\\\\", \"u\": \"x\\\\\\\"y\\\\\", \"n\": -12.5e-3,\"m\":7,\n"
      "  \"a\": [1,2 , 3\n,4], \"o\": {\"k\": [true,false ,null], \"e\": {}, \"f\": []},\t\"z\": 0}",
      "[\"\\u00e9\\\"\", [[[]]], 18446744073709551615, -9223372036854775808, 1e300]",
      "42",
      "\"alone\"",
      "  \n true",
      "[0]"};
  for (const std::string& text : texts) {
    SCOPED_TRACE(text);
    ExpectPositionsAtTokens(Json::Parse(text, "p.json"), text);
  }
}

TEST(Json, SyntaxErrorsSayWhatWasExpected) {
  struct Case {
    const char* text;
    const char* words;
    int line, column;
  } cases[] = {{"{\"a\": 1\n \"b\": 2}", "expected ',' or '}' in an object", 2, 2},
               {"[1 2]", "expected ',' or ']' in an array", 1, 4},
               {"{\"a\": 1, }", "expected a quoted key", 1, 10},
               {"{\"key\" 1}", "expected ':' after the key \"key\"", 1, 8},
               {"{\"a\": 1, \"a\": 2}", "duplicate key \"a\"", 1, 13},
               {"[1, Infinity]", "NaN and Infinity are not JSON numbers", 1, 5},
               {"{\"a\": 1e999}", "number out of range", 1, 7},
               {"{\"a\": 1} x", "unexpected text after the JSON document", 1, 10},
               {"[\"\xff\"]", "invalid string", 1, 3},
               {"", "unexpected end of input", 1, 1}};
  for (const auto& c : cases) {
    try {
      Json::Parse(c.text, "bad.json");
      FAIL() << "accepted " << c.text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(c.words), std::string::npos) << c.text << ": " << e.what();
      EXPECT_EQ(e.where().line, c.line) << c.text << ": " << e.what();
      EXPECT_EQ(e.where().column, c.column) << c.text << ": " << e.what();
      EXPECT_EQ(std::string(e.what()).find("json.exception"), std::string::npos) << e.what();
    }
  }
}

TEST(Json, NestingIsLimited) {
  const auto nested = [](int depth) { return std::string(depth, '[') + std::string(depth, ']'); };
  EXPECT_NO_THROW(Json::Parse(nested(200), "deep.json"));
  try {
    Json::Parse(nested(201), "deep.json");
    FAIL() << "201 nested arrays accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nested too deeply"), std::string::npos) << e.what();
    EXPECT_EQ(e.where().column, 201);
  }
}

TEST(Json, WhatIsWrittenReadsBack) {
  Json root = Json::Object();
  root.Set("bad utf-8", "caf\xe9");  // Latin-1, not UTF-8: written as U+FFFD
  root.Set("control", std::string("a\tb\x01", 4));
  root.Set("big", Json(std::int64_t{9007199254740993}));
  root.Set("flat", Json::ArrayOf(std::vector<double>{1, 0.5}));
  const std::string text = root.Dump();
  EXPECT_NE(text.find("\"flat\": [1, 0.5]"), std::string::npos) << text;
  const Json back = Json::Parse(text, "rt.json");
  EXPECT_EQ(back.Get("bad utf-8")->as_string(), "caf\xef\xbf\xbd");
  EXPECT_EQ(back.Get("control")->as_string(), std::string("a\tb\x01", 4));
  EXPECT_TRUE(back.Get("big")->is_integer());
}

}  // namespace
}  // namespace hull
