// Issue 14, base layer: a ".gz" that is not gzip is refused, a gzip bomb is
// refused after the cap (not after inflating it whole), and error messages
// are bounded in length with binary bytes escaped.
#include <gtest/gtest.h>
#include <zlib.h>

#include <chrono>
#include <filesystem>

#include "base/csv.h"
#include "base/error.h"
#include "base/file_checks.h"
#include "base/file_io.h"
#include "base/printable.h"

namespace hull {
namespace {

std::string TempPath(const std::string& name) {
  const auto p = std::filesystem::path(::testing::TempDir()) / "hi_robust_base" / name;
  std::filesystem::create_directories(p.parent_path());
  return p.string();
}

TEST(RobustInput, GzNameWithoutGzipDataIsRefusedAsNotGzip) {
  const std::string p = TempPath("hull.stl.gz");
  WriteFileAtomic(p, "solid hull\nendsolid hull\n");
  try {
    ReadFileToString(p);
    FAIL() << "a .gz file that is not gzip was read as raw data";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, p);
    EXPECT_NE(std::string(e.what()).find("not gzip"), std::string::npos) << e.what();
  }
  // The same bytes under a plain name read as they are.
  const std::string plain = TempPath("hull.stl");
  WriteFileAtomic(plain, "solid hull\nendsolid hull\n");
  EXPECT_EQ(ReadFileToString(plain), "solid hull\nendsolid hull\n");
}

TEST(RobustInput, GzipBombIsRefusedAtTheCap) {
  // 128 MiB of zeros compress about 1000 times.
  const std::string p = TempPath("bomb.stl.gz");
  gzFile f = gzopen(p.c_str(), "wb1");
  ASSERT_NE(f, nullptr);
  const std::string chunk(1 << 20, '\0');
  for (int i = 0; i < 128; ++i) ASSERT_EQ(gzwrite(f, chunk.data(), static_cast<unsigned>(chunk.size())), 1 << 20);
  gzclose(f);
  const auto compressed = std::filesystem::file_size(p);
  ASSERT_LT(compressed * kMaxGzipRatio, std::size_t{128} << 20);
  try {
    ReadFileToString(p);
    FAIL() << "a gzip bomb was inflated whole";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("decompression bomb"), std::string::npos) << e.what();
  }
  EXPECT_EQ(MaxDecompressedSize(1000), kGzipFloorBytes);
  EXPECT_EQ(MaxDecompressedSize(std::size_t{10} << 20), (std::size_t{10} << 20) * kMaxGzipRatio);
}

TEST(RobustInput, PrintableTextEscapesBinaryAndBoundsLength) {
  EXPECT_EQ(PrintableText("plain text, tab\there"), "plain text, tab\there");
  EXPECT_EQ(PrintableText(std::string("a\0b\x1b[2Jc", 8)), "a\\x00b\\x1b[2Jc");
  EXPECT_EQ(PrintableText("\xff\xfe ok"), "\\xff\\xfe ok");
  EXPECT_EQ(PrintableText("Gr\xc3\xbc\xc3\x9f"
                          "e 3\xc2\xb0"),
            "Gr\xc3\xbc\xc3\x9f"
            "e 3\xc2\xb0");                   // valid UTF-8 kept
  EXPECT_EQ(PrintableText("\xc3"), "\\xc3");  // a truncated sequence
  const std::string cut = PrintableText(std::string(5000, 'x'), 100);
  EXPECT_EQ(cut, std::string(100, 'x') + "... (4900 more bytes)");
}

TEST(RobustInput, AHugeMalformedHeaderIsNotEchoedWhole) {
  // A 100 kB header line of binary garbage with a duplicated column name.
  std::string name;
  for (int i = 0; i < 50000; ++i) name += static_cast<char>(i % 2 ? '\x01' : 'q');
  const std::string text = name + "," + name + "\n1,2\n";
  try {
    CsvReader r(text, "nav.csv");
    FAIL() << "a duplicated header was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_LT(what.size(), kMaxPrintedPath + kMaxPrintedField + kMaxPrintedMessage + 100) << what.size();
    EXPECT_EQ(what.find('\x01'), std::string::npos) << "a control byte was printed raw";
    EXPECT_NE(what.find("nav.csv"), std::string::npos);
    EXPECT_NE(what.find("more bytes"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace hull
