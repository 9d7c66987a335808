#include "base/file_io.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>

#include "base/error.h"

namespace hull {
namespace {

std::string TempPath(const std::string& name) { return (std::filesystem::path(::testing::TempDir()) / name).string(); }

TEST(FileIo, AtomicWriteAndRead) {
  const std::string p = TempPath("hi_file_io/sub/a.txt");
  WriteFileAtomic(p, "hello");
  EXPECT_EQ(ReadFileToString(p), "hello");
  WriteFileAtomic(p, "again");
  EXPECT_EQ(ReadFileToString(p), "again");
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(p).parent_path())) {
    EXPECT_EQ(e.path().filename(), "a.txt") << "temporary file left behind";
  }
}

TEST(FileIo, ReadsGzip) {
  const std::string p = TempPath("hi_file_io/b.txt.gz");
  std::filesystem::create_directories(std::filesystem::path(p).parent_path());
  gzFile f = gzopen(p.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  std::string big(200000, 'x');
  gzwrite(f, big.data(), static_cast<unsigned>(big.size()));
  gzclose(f);
  EXPECT_EQ(ReadFileToString(p), big);
}

TEST(FileIo, MissingAndCorruptFilesNameTheFile) {
  try {
    ReadFileToString(TempPath("does/not/exist.csv"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(e.where().file.find("exist.csv"), std::string::npos);
  }
  const std::string p = TempPath("hi_file_io/bad.gz");
  {
    std::ofstream out(p, std::ios::binary);
    out << "\x1f\x8b"
        << "garbage that is not deflate";
  }
  EXPECT_THROW(ReadFileToString(p), InputError);
}

TEST(FileIo, MeshExtension) {
  EXPECT_EQ(MeshExtension("/a/Hull.STL.gz"), ".stl");
  EXPECT_EQ(MeshExtension("x.ply"), ".ply");
  EXPECT_EQ(MeshExtension("noext"), "");
}

}  // namespace
}  // namespace hull
