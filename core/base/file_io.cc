#include "base/file_io.h"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <unistd.h>

#include "base/error.h"
#include "base/file_checks.h"

namespace hull {

bool EndsWith(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string AsciiLower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string MeshExtension(const std::string& path) {
  std::string p = AsciiLower(path);
  if (EndsWith(p, ".gz")) p.resize(p.size() - 3);
  return std::filesystem::path(p).extension().string();
}

std::size_t MaxDecompressedSize(std::size_t compressed_bytes) {
  return std::max<std::size_t>(kGzipFloorBytes, compressed_bytes * kMaxGzipRatio);
}

std::string ReadFileToString(const std::string& path, std::uint64_t max_bytes, const std::string& limit_reason) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError({path, 0, 0, ""}, std::filesystem::exists(path, ec) ? "is not a regular file" : "no such file");
  }
  if (const std::uintmax_t size = std::filesystem::file_size(path, ec); !ec && size > max_bytes) {
    char text[160];
    std::snprintf(text, sizeof text, "refused: the file is %.1f MiB, more than the %.1f MiB ",
                  static_cast<double>(size) / (1 << 20), static_cast<double>(max_bytes) / (1 << 20));
    throw InputError({path, 0, 0, ""},
                     text + (limit_reason.empty() ? "HullInspect reads from one file" : limit_reason));
  }
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw InputError({path, 0, 0, ""}, std::string("cannot open: ") + std::strerror(errno));
  std::string raw;
  raw.resize(static_cast<std::size_t>(std::filesystem::file_size(path, ec)));
  const std::size_t got = raw.empty() ? 0 : std::fread(raw.data(), 1, raw.size(), f);
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed || got != raw.size()) throw InputError({path, 0, 0, ""}, "read error");
  const bool gz =
      raw.size() >= 2 && static_cast<unsigned char>(raw[0]) == 0x1f && static_cast<unsigned char>(raw[1]) == 0x8b;
  if (!gz) {
    if (EndsWith(path, ".gz") || EndsWith(path, ".GZ")) {
      throw InputError({path, 0, 0, ""},
                       "not gzip: the name ends in .gz but the file does not begin with the gzip "
                       "signature (1f 8b); expected a gzip-compressed file");
    }
    return raw;
  }
  const std::size_t cap = std::min<std::uint64_t>(MaxDecompressedSize(raw.size()), max_bytes);
  z_stream zs{};
  if (inflateInit2(&zs, 15 + 32) != Z_OK) throw InputError({path, 0, 0, ""}, "cannot initialise zlib");
  std::string out;
  out.resize(std::max<std::size_t>(raw.size() * 4, 1 << 16));
  zs.next_in = reinterpret_cast<Bytef*>(raw.data());
  zs.avail_in = static_cast<uInt>(raw.size());
  int rc = Z_OK;
  while (true) {
    if (zs.total_out > cap) {
      inflateEnd(&zs);
      throw InputError({path, 0, 0, ""}, "refused: the gzip data expands more than " + std::to_string(kMaxGzipRatio) +
                                             " times (past " + std::to_string(cap >> 20) + " MiB from " +
                                             std::to_string(raw.size()) +
                                             " bytes); real meshes and survey files compress a few times, so this is a "
                                             "decompression bomb or a corrupt file");
    }
    if (zs.total_out >= out.size()) out.resize(std::min(out.size() * 2, cap + 1));
    zs.next_out = reinterpret_cast<Bytef*>(out.data() + zs.total_out);
    zs.avail_out = static_cast<uInt>(std::min<std::size_t>(out.size() - zs.total_out, 1u << 30));
    rc = inflate(&zs, Z_NO_FLUSH);
    if (rc == Z_STREAM_END) {
      // Concatenated gzip members: continue with the next one.
      if (zs.avail_in > 0) {
        std::size_t produced = zs.total_out;
        inflateReset(&zs);
        zs.total_out = produced;
        continue;
      }
      break;
    }
    if (rc != Z_OK && rc != Z_BUF_ERROR) {
      inflateEnd(&zs);
      throw InputError({path, 0, 0, ""}, std::string("corrupt gzip data: ") + (zs.msg ? zs.msg : "inflate failed"));
    }
    if (rc == Z_BUF_ERROR && zs.avail_in == 0) {
      inflateEnd(&zs);
      throw InputError({path, 0, 0, ""}, "truncated gzip data");
    }
  }
  out.resize(zs.total_out);
  inflateEnd(&zs);
  return out;
}

std::string OutputLocationProblem(const std::string& path, OutputKind kind) {
  namespace fs = std::filesystem;
  const bool folder = kind == OutputKind::kFolder;
  if (path.empty()) return "no output location given";
  std::error_code ec;
  const fs::path p(path);
  const bool exists = fs::exists(p, ec);
  if (exists && folder && !fs::is_directory(p, ec))
    return "'" + path + "' is a file; expected a folder for the results";
  if (exists && !folder && fs::is_directory(p, ec)) return "'" + path + "' is a folder; expected a file name";
  fs::path dir = exists && folder ? p : p.parent_path();
  if (dir.empty()) dir = ".";
  if (!fs::exists(dir, ec)) return "the folder '" + dir.string() + "' does not exist; create it first";
  if (!fs::is_directory(dir, ec)) return "'" + dir.string() + "' is not a folder";
  const fs::path probe = dir / (".hullinspect-write-test-" + std::to_string(static_cast<long long>(::getpid())));
  std::FILE* f = std::fopen(probe.c_str(), "wx");
  if (!f) {
    const int err = errno;
    return "cannot write in '" + dir.string() + "': " + std::strerror(err) +
           (err == EROFS || err == EACCES || err == EPERM ? " (read-only)" : "");
  }
  std::fclose(f);
  fs::remove(probe, ec);
  return "";
}

void WriteFileAtomic(const std::string& path, std::string_view data) {
  namespace fs = std::filesystem;
  fs::path target(path);
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  fs::path tmp = target;
  tmp += ".tmp-" + std::to_string(static_cast<long long>(::getpid()));
  {
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw std::runtime_error("cannot write " + tmp.string() + ": " + std::strerror(errno));
    bool ok = std::fwrite(data.data(), 1, data.size(), f) == data.size();
    ok = (std::fflush(f) == 0) && ok;
    ok = (std::fclose(f) == 0) && ok;
    if (!ok) {
      fs::remove(tmp);
      throw std::runtime_error("cannot write " + tmp.string() + ": " + std::strerror(errno));
    }
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp);
    throw std::runtime_error("cannot rename " + tmp.string() + " to " + path + ": " + ec.message());
  }
}

}  // namespace hull
