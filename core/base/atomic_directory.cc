#include "base/atomic_directory.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace hull {
namespace {

namespace fs = std::filesystem;

// Hidden siblings left by writers that no longer run (killed): removed.
void RemoveStaleSiblings(const fs::path& dir) {
  const std::string prefix = "." + dir.filename().string() + ".writing-";
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir.parent_path(), ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
    if (pid > 0 && pid != static_cast<long>(::getpid()) && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
      fs::remove_all(e.path(), ec);
    }
  }
}

}  // namespace

void WriteDirectoryAtomic(const std::string& dir_name, const std::function<void(const std::string& tmp)>& write) {
  fs::path dir = fs::absolute(dir_name).lexically_normal();
  if (dir.filename().empty()) dir = dir.parent_path();
  fs::create_directories(dir.parent_path());
  RemoveStaleSiblings(dir);
  const fs::path tmp =
      dir.parent_path() / ("." + dir.filename().string() + ".writing-" + std::to_string(static_cast<long>(::getpid())));
  std::error_code ec;
  fs::remove_all(tmp, ec);
  fs::create_directory(tmp);
  try {
    write(tmp.string());
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
  if (!fs::exists(dir)) {
    fs::rename(tmp, dir, ec);
    if (ec) {
      fs::remove_all(tmp);
      throw std::runtime_error("cannot rename " + tmp.string() + " to " + dir.string() + ": " + ec.message());
    }
    return;
  }
  // Swap in one step; tmp then holds the previous results.
  if (::renameat2(AT_FDCWD, tmp.c_str(), AT_FDCWD, dir.c_str(), RENAME_EXCHANGE) == 0) {
    fs::remove_all(tmp, ec);
    return;
  }
  // No RENAME_EXCHANGE here: move the old folder aside, then the new one in.
  const fs::path old =
      dir.parent_path() / ("." + dir.filename().string() + ".old-" + std::to_string(static_cast<long>(::getpid())));
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

}  // namespace hull
