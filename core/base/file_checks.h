// Checks on the files HullInspect reads and writes (issue 14), implemented
// with ReadFileToString and WriteFileAtomic in file_io.cc.
#pragma once

#include <cstddef>
#include <string>

namespace hull {

// ReadFileToString refuses a name ending in ".gz" without the gzip magic
// bytes ("not gzip"), and gzip data that inflates past MaxDecompressedSize
// (a decompression bomb): inflation stops at the cap, so the refusal is
// quick and needs no more memory than the cap. The cap is kMaxGzipRatio
// times the compressed size, never less than kGzipFloorBytes (any file that
// inflates to 64 MiB or less reads). Meshes and survey CSV compress 2-10
// times; 50 leaves room for very regular files while a bomb (10 M
// degenerate STL triangles, 500 MB from 2.9 MB) stops after 145 MB.
constexpr std::size_t kMaxGzipRatio = 50;
constexpr std::size_t kGzipFloorBytes = std::size_t{64} << 20;
std::size_t MaxDecompressedSize(std::size_t compressed_bytes);

// What stops a job from writing its results at path, checked before the
// work starts ("" when nothing does): for a folder (kFolder), path must be
// an existing folder or a new name in an existing folder; for a file, a new
// or existing file (not a folder) in an existing folder; and that folder
// must accept a new file (probed by creating and removing one, so read-only
// mounts and permissions are both caught, even for root). Plain words, no
// std::filesystem text.
enum class OutputKind { kFolder, kFile };
std::string OutputLocationProblem(const std::string& path, OutputKind kind);

}  // namespace hull
