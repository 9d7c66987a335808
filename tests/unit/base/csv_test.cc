#include "base/csv.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace hull {
namespace {

TEST(Csv, ReadsColumnsByNameInAnyOrder) {
  const std::string text = "b,a,extra\n2,1,x\n4,3,y\n";
  CsvReader r(text, "t.csv");
  const int a = r.Require("a"), b = r.Require("b");
  EXPECT_EQ(r.Find("missing"), -1);
  ASSERT_TRUE(r.Next());
  EXPECT_EQ(r.Int(a), 1);
  EXPECT_EQ(r.Double(b), 2.0);
  ASSERT_TRUE(r.Next());
  EXPECT_EQ(r.line(), 3);
  EXPECT_EQ(r.Int(a), 3);
  EXPECT_FALSE(r.Next());
}

TEST(Csv, HandlesCrLfBomQuotesAndBlankLines) {
  const std::string text = "\xEF\xBB\xBFid,name\r\n1,\"a, \"\"quoted\"\" name\"\r\n\r\n2,plain\r\n";
  CsvReader r(text, "t.csv");
  const int id = r.Require("id"), name = r.Require("name");
  ASSERT_TRUE(r.Next());
  EXPECT_EQ(r.Field(name), "a, \"quoted\" name");
  ASSERT_TRUE(r.Next());
  EXPECT_EQ(r.Int(id), 2);
  EXPECT_EQ(r.line(), 4);
  EXPECT_FALSE(r.Next());
}

TEST(Csv, RejectsNanInfAndTextWithLocation) {
  for (const char* bad : {"nan", "inf", "-inf", "NaN", "Infinity", "abc", "1.5x", "0x10"}) {
    const std::string text = std::string("k,v\n1,") + bad + "\n";
    CsvReader r(text, "f.csv");
    const int v = r.Require("v");
    ASSERT_TRUE(r.Next());
    try {
      r.Double(v);
      FAIL() << "accepted " << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, "f.csv");
      EXPECT_EQ(e.where().line, 2);
      EXPECT_EQ(e.where().column, 3);
      EXPECT_EQ(e.where().field, "v");
    }
  }
}

TEST(Csv, EmptyFieldIsMissingOrError) {
  CsvReader r("a,b\n1,\n", "f.csv");
  const int a = r.Require("a"), b = r.Require("b");
  ASSERT_TRUE(r.Next());
  EXPECT_FALSE(r.OptionalDouble(b).has_value());
  EXPECT_EQ(*r.OptionalDouble(a), 1.0);
  EXPECT_THROW(r.Double(b), InputError);
}

TEST(Csv, FieldCountMismatchAndHeaderProblems) {
  {
    CsvReader r("a,b\n1,2,3\n", "f.csv");
    EXPECT_THROW(r.Next(), InputError);
  }
  EXPECT_THROW(CsvReader("", "f.csv"), InputError);
  EXPECT_THROW(CsvReader("a,a\n", "f.csv"), InputError);
  CsvReader r("a\n", "f.csv");
  try {
    r.Require("b");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 1);
    EXPECT_NE(std::string(e.what()).find("'b'"), std::string::npos);
  }
  EXPECT_THROW(
      {
        CsvReader q("a\n\"open\n", "f.csv");
        q.Next();
      },
      InputError);
}

TEST(Csv, IntegersAreStrict) {
  CsvReader r("a\n1.0\n", "f.csv");
  const int a = r.Require("a");
  ASSERT_TRUE(r.Next());
  EXPECT_THROW(r.Int(a), InputError);
}

TEST(Csv, DoublesRoundTripBitExactly) {
  const double values[] = {
      0.1, 1.0 / 3.0, -1e-300, 6.02214076e23, 183.00000000000003, 5e-324, std::numeric_limits<double>::max()};
  CsvWriter w({"v"});
  for (double v : values) {
    w.Add(v);
    w.EndRow();
  }
  CsvReader r(w.text(), "w.csv");
  const int c = r.Require("v");
  for (double v : values) {
    ASSERT_TRUE(r.Next());
    EXPECT_EQ(r.Double(c), v);
  }
}

TEST(Csv, WriterQuotesWhenNeeded) {
  CsvWriter w({"a", "b"});
  w.Add(std::string_view("x,y")).Add(std::string_view("say \"hi\""));
  w.EndRow();
  CsvReader r(w.text(), "w.csv");
  ASSERT_TRUE(r.Next());
  EXPECT_EQ(r.Field(0), "x,y");
  EXPECT_EQ(r.Field(1), "say \"hi\"");
}

}  // namespace
}  // namespace hull
