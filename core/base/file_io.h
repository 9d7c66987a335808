// Whole-file reading (transparently gunzipping *.gz) and atomic writing
// (write a sibling temporary, then rename), so a crash never leaves a
// half-written file in place of the user's.
#pragma once

#include <string>
#include <string_view>

namespace hull {

// Reads a file into memory; a name ending in ".gz" (or gzip magic bytes) is
// decompressed. Throws InputError naming the file when it cannot be read.
std::string ReadFileToString(const std::string& path);
// Writes data to path atomically; throws std::runtime_error on failure.
void WriteFileAtomic(const std::string& path, std::string_view data);
// Lower-case extension without the ".gz" suffix: "hull.stl.gz" -> ".stl".
std::string MeshExtension(const std::string& path);
bool EndsWith(std::string_view s, std::string_view suffix);
// s with the ASCII letters in lower case (extensions, keys).
std::string AsciiLower(std::string s);

}  // namespace hull
