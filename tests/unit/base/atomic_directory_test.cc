// A folder is replaced as a whole: a writer that fails, or a child process
// killed in the middle of writing, leaves the previous folder intact and
// complete; a writer that finishes replaces it entirely. (Results folders,
// their manifest and the user's files in them: tests/unit/results.)
#include "base/atomic_directory.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include "base/file_io.h"

namespace hull {
namespace {

namespace fs = std::filesystem;

fs::path Fresh(const std::string& name) {
  const fs::path p = fs::path(::testing::TempDir()) / name;
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

// The folder's files and their contents, sorted by name.
std::vector<std::pair<std::string, std::string>> Contents(const fs::path& dir) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) out.emplace_back(fs::relative(e.path(), dir).string(), ReadFileToString(e.path()));
  }
  std::sort(out.begin(), out.end());
  return out;
}

void WriteRun(const std::string& tmp, const std::string& run, int files) {
  for (int i = 0; i < files; ++i) WriteFileAtomic(tmp + "/file" + std::to_string(i) + ".txt", run);
}

TEST(AtomicDirectory, ReplacesTheWholeFolder) {
  const fs::path root = Fresh("hi_atomic_replace");
  const std::string dir = (root / "results").string();
  WriteDirectoryAtomic(dir, [](const std::string& tmp) { WriteRun(tmp, "run 1", 3); });
  EXPECT_EQ(Contents(dir).size(), 3u);
  // A second run with fewer files: none of the first run's remain.
  WriteDirectoryAtomic(dir, [](const std::string& tmp) { WriteRun(tmp, "run 2", 2); });
  const auto c = Contents(dir);
  ASSERT_EQ(c.size(), 2u);
  for (const auto& [name, text] : c) EXPECT_EQ(text, "run 2") << name;
  // Nothing else is left beside it.
  int siblings = 0;
  for (const auto& e : fs::directory_iterator(root)) siblings += e.path().filename() != "results";
  EXPECT_EQ(siblings, 0);
}

TEST(AtomicDirectory, AFailedRunLeavesThePreviousResults) {
  const fs::path root = Fresh("hi_atomic_fail");
  const std::string dir = (root / "results").string();
  WriteDirectoryAtomic(dir, [](const std::string& tmp) { WriteRun(tmp, "good", 3); });
  const auto before = Contents(dir);
  EXPECT_THROW(WriteDirectoryAtomic(dir,
                                    [](const std::string& tmp) {
                                      WriteRun(tmp, "half", 1);
                                      throw std::runtime_error("disk full");
                                    }),
               std::runtime_error);
  EXPECT_EQ(Contents(dir), before);
  int siblings = 0;
  for (const auto& e : fs::directory_iterator(root)) siblings += e.path().filename() != "results";
  EXPECT_EQ(siblings, 0);
}

TEST(AtomicDirectory, AKilledRunLeavesThePreviousResults) {
  const fs::path root = Fresh("hi_atomic_kill");
  const std::string dir = (root / "results").string();
  WriteDirectoryAtomic(dir, [](const std::string& tmp) { WriteRun(tmp, "good", 4); });
  const auto before = Contents(dir);
  const fs::path marker = root / "child-wrote-half";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    // The child writes half of a new run, says so, and hangs until killed.
    WriteDirectoryAtomic(dir, [&](const std::string& tmp) {
      WriteRun(tmp, "half", 2);
      WriteFileAtomic(marker.string(), "");
      for (;;) ::pause();
    });
    ::_exit(0);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!fs::exists(marker) && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(fs::exists(marker));
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(Contents(dir), before);
  // The killed run's hidden folder is removed by the next write.
  int stale = 0;
  for (const auto& e : fs::directory_iterator(root)) stale += e.path().filename().string().rfind(".results.", 0) == 0;
  EXPECT_EQ(stale, 1);
  WriteDirectoryAtomic(dir, [](const std::string& tmp) { WriteRun(tmp, "next", 1); });
  stale = 0;
  for (const auto& e : fs::directory_iterator(root)) stale += e.path().filename().string().rfind(".results.", 0) == 0;
  EXPECT_EQ(stale, 0);
  ASSERT_EQ(Contents(dir).size(), 1u);
}

TEST(AtomicDirectory, AFolderLeftAsideByAKilledSwapIsPutBack) {
  // Where the file system has no RENAME_EXCHANGE the swap is two renames; a
  // writer killed between them leaves the folder aside as ".NAME.old-PID".
  // The next write puts it back before anything else, so even a write that
  // then fails leaves the previous folder whole.
  const fs::path root = Fresh("hi_atomic_old");
  const fs::path aside = root / ".results.old-999999999";  // no such process
  fs::create_directories(aside);
  WriteFileAtomic((aside / "file0.txt").string(), "previous");
  const std::string dir = (root / "results").string();
  EXPECT_THROW(WriteDirectoryAtomic(dir, [](const std::string&) { throw std::runtime_error("disk full"); }),
               std::runtime_error);
  ASSERT_EQ(Contents(dir).size(), 1u);
  EXPECT_EQ(Contents(dir)[0].second, "previous");
  EXPECT_FALSE(fs::exists(aside));
}

}  // namespace
}  // namespace hull
