#include "base/atomic_directory.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
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

// The names a run wrote at the top of its folder, kept in the folder, so the
// next run knows which entries are results and which are the user's.
constexpr const char* kManifest = ".hullinspect-results";

std::set<std::string> ReadManifest(const fs::path& dir) {
  std::set<std::string> names;
  std::ifstream in(dir / kManifest);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) names.insert(line);
  }
  return names;
}

void WriteManifest(const fs::path& tmp) {
  std::ofstream out(tmp / kManifest);
  for (const auto& e : fs::directory_iterator(tmp)) {
    const std::string name = e.path().filename().string();
    if (name != kManifest) out << name << '\n';
  }
  if (!out) throw std::runtime_error("cannot write " + (tmp / kManifest).string());
}

// `from` recreated at `to` with hard links (a copy where links fail), so the
// previous folder stays whole until the swap.
void LinkTree(const fs::path& from, const fs::path& to) {
  const fs::file_status st = fs::symlink_status(from);
  if (fs::is_symlink(st)) {
    fs::copy_symlink(from, to);
  } else if (fs::is_directory(st)) {
    fs::create_directory(to);
    for (const auto& e : fs::directory_iterator(from)) LinkTree(e.path(), to / e.path().filename());
  } else {
    std::error_code ec;
    fs::create_hard_link(from, to, ec);
    if (ec) fs::copy_file(from, to);
  }
}

// Entries of the previous folder that are not results of a run (the user's
// files, a survey saved there, a report) and that this run did not write:
// carried into the new folder.
void CarryOverUserEntries(const fs::path& dir, const fs::path& tmp) {
  const std::set<std::string> results = ReadManifest(dir);
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == kManifest || results.count(name)) continue;
    if (fs::exists(fs::symlink_status(tmp / name))) continue;
    LinkTree(e.path(), tmp / name);
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
    WriteManifest(tmp);
    if (fs::is_directory(dir)) CarryOverUserEntries(dir, tmp);
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
