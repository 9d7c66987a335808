#include "results/file_hash.h"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "base/error.h"

namespace hull {
namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t kOffset = 14695981039346656037ull;
constexpr std::uint64_t kPrime = 1099511628211ull;

void Mix(std::uint64_t& h, std::string_view bytes) {
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= kPrime;
  }
}

std::string Hex(std::uint64_t h) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "fnv1a64:%016llx", static_cast<unsigned long long>(h));
  return buf;
}

// Feeds the file's bytes into h; false when it does not exist.
bool MixFile(std::uint64_t& h, const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, 0, 0, ""}, "cannot be read (to fingerprint it)");
  std::string block(1 << 16, '\0');
  while (in) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    Mix(h, std::string_view(block.data(), static_cast<std::size_t>(in.gcount())));
  }
  if (in.bad()) throw InputError({path, 0, 0, ""}, "cannot be read (to fingerprint it)");
  return true;
}

}  // namespace

std::string HashText(std::string_view bytes) {
  std::uint64_t h = kOffset;
  Mix(h, bytes);
  return Hex(h);
}

std::string FileHash(const std::string& path) {
  std::uint64_t h = kOffset;
  if (!MixFile(h, path)) throw InputError({path, 0, 0, ""}, "no such file (to fingerprint it)");
  return Hex(h);
}

std::string FilesHash(const std::vector<std::string>& paths) {
  std::uint64_t h = kOffset;
  for (const std::string& p : paths) {
    Mix(h, fs::path(p).filename().string());
    std::error_code ec;
    const auto size = fs::file_size(p, ec);
    Mix(h, ec ? std::string("absent") : std::to_string(size));
    MixFile(h, p);
  }
  return Hex(h);
}

std::string SurveyHash(const std::string& bundle_dir) {
  const fs::path d(bundle_dir);
  return FilesHash({(d / "survey.json").string(), (d / "nav.csv").string()});
}

std::string SequenceHash(const std::string& sequence_dir) {
  const fs::path d(sequence_dir);
  return FilesHash({(d / "sonar.json").string(), (d / "controls.csv").string()});
}

}  // namespace hull
