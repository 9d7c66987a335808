#include "base/atomic_directory.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace hull {
namespace {

namespace fs = std::filesystem;

fs::path Normal(const std::string& dir_name) {
  fs::path dir = fs::absolute(dir_name).lexically_normal();
  if (dir.filename().empty()) dir = dir.parent_path();
  return dir;
}

fs::path Sibling(const fs::path& dir, const char* kind, long pid) {
  return dir.parent_path() / ("." + dir.filename().string() + "." + kind + "-" + std::to_string(pid));
}

// The pid in a sibling's name when that process no longer runs (killed), else 0.
long DeadWriter(const std::string& name, const std::string& prefix) {
  if (name.rfind(prefix, 0) != 0) return 0;
  const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
  if (pid <= 0 || pid == static_cast<long>(::getpid())) return 0;
  return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH ? pid : 0;
}

// Hidden siblings left by writers that no longer run: their half-written
// folders are removed; a previous folder moved aside (".old-", the two-rename
// swap) is put back when the writer died before the new one went in.
void CleanUpAfterDeadWriters(const fs::path& dir) {
  const std::string writing = "." + dir.filename().string() + ".writing-";
  const std::string old = "." + dir.filename().string() + ".old-";
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir.parent_path(), ec)) {
    const std::string name = e.path().filename().string();
    if (DeadWriter(name, writing)) {
      fs::remove_all(e.path(), ec);
    } else if (DeadWriter(name, old)) {
      if (!fs::exists(fs::symlink_status(dir))) {
        fs::rename(e.path(), dir, ec);
      } else {
        fs::remove_all(e.path(), ec);
      }
    }
  }
}

// No RENAME_EXCHANGE here: move the old folder aside, then the new one in.
void SwapInTwoRenames(const fs::path& tmp, const fs::path& dir) {
  std::error_code ec;
  const fs::path old = Sibling(dir, "old", static_cast<long>(::getpid()));
  fs::remove_all(old, ec);
  fs::rename(dir, old, ec);
  if (ec) {
    fs::remove_all(tmp);
    throw std::runtime_error("cannot move " + dir.string() + " aside: " + ec.message());
  }
  fs::rename(tmp, dir, ec);
  if (ec) {
    fs::rename(old, dir);
    fs::remove_all(tmp);
    throw std::runtime_error("cannot rename " + tmp.string() + " to " + dir.string() + ": " + ec.message());
  }
  fs::remove_all(old, ec);
}

}  // namespace

std::string AtomicDirectorySibling(const std::string& dir) {
  return Sibling(Normal(dir), "writing", static_cast<long>(::getpid())).string();
}

void WriteDirectoryAtomic(const std::string& dir_name, const std::function<void(const std::string& tmp)>& write) {
  const fs::path dir = Normal(dir_name);
  fs::create_directories(dir.parent_path());
  CleanUpAfterDeadWriters(dir);
  const fs::path tmp = Sibling(dir, "writing", static_cast<long>(::getpid()));
  std::error_code ec;
  fs::remove_all(tmp, ec);
  fs::create_directory(tmp);
  try {
    write(tmp.string());
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
  if (!fs::exists(fs::symlink_status(dir))) {
    fs::rename(tmp, dir, ec);
    if (ec) {
      fs::remove_all(tmp);
      throw std::runtime_error("cannot rename " + tmp.string() + " to " + dir.string() + ": " + ec.message());
    }
    return;
  }
  // Swap in one step; tmp then holds the previous folder.
  if (::renameat2(AT_FDCWD, tmp.c_str(), AT_FDCWD, dir.c_str(), RENAME_EXCHANGE) == 0) {
    fs::remove_all(tmp, ec);
    return;
  }
  SwapInTwoRenames(tmp, dir);
}

}  // namespace hull
