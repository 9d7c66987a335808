// Whole-file reading (transparently gunzipping *.gz) and atomic writing
// (write a sibling temporary, then rename), so a crash never leaves a
// half-written file in place of the user's.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace hull {

// The most one whole-file read takes into memory (2 GiB): a larger file is
// refused from its size, before any allocation (a 20 GB sparse file named
// as an image or a CSV is an error naming it, not std::bad_alloc).
inline constexpr std::uint64_t kMaxFileBytes = std::uint64_t{2} << 30;

// Reads a file into memory; a name ending in ".gz" (or gzip magic bytes) is
// decompressed. Throws InputError naming the file when it cannot be read or
// is larger than max_bytes (`limit_reason` says why that bound, for the
// message: "a controls row per step").
std::string ReadFileToString(const std::string& path, std::uint64_t max_bytes = kMaxFileBytes,
                             const std::string& limit_reason = "");
// Writes data to path atomically; throws std::runtime_error on failure.
void WriteFileAtomic(const std::string& path, std::string_view data);
// Lower-case extension without the ".gz" suffix: "hull.stl.gz" -> ".stl".
std::string MeshExtension(const std::string& path);
bool EndsWith(std::string_view s, std::string_view suffix);
// s with the ASCII letters in lower case (extensions, keys).
std::string AsciiLower(std::string s);

}  // namespace hull
