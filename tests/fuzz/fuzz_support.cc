#include "fuzz_support.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace hull::fuzz {
namespace fs = std::filesystem;

const std::string& ScratchDir() {
  // The path also lives in a plain array, which the exit handler can still
  // read after the string's destructor has run.
  static char path[4096];
  static const std::string dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::snprintf(path, sizeof path, "%s/hi-fuzz-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(path)) throw std::runtime_error("cannot make a scratch folder");
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(path, ec);
    });
    return std::string(path);
  }();
  return dir;
}

void CopyTree(const std::string& from, const std::string& to) {
  fs::remove_all(to);
  fs::copy(from, to, fs::copy_options::recursive);
}

void WriteInput(const std::string& path, const std::uint8_t* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace hull::fuzz
