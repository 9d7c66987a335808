#include "base/json.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace hull
