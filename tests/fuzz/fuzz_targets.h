// What the harnesses run, compiled once (hull_fuzztargets) and shared by the
// per-file harness executables (harness.cc, configured by compile
// definitions), so each harness only adds a tiny translation unit.
#pragma once

#include <cstddef>
#include <cstdint>

namespace hull::fuzz {

// Replaces `file` of a copy of the valid bundle (or acoustic sequence, with
// `sonar`) in `base` by the input and runs the reader and the validator.
void BundleFile(const char* base, const char* file, bool sonar, const std::uint8_t* data, std::size_t size);

// The same for an acoustic sequence, then, when it reads, the whole sonar
// chain on it (sonar_fuzz.cc, the hull_fuzzsonar library).
void SonarChainFile(const char* base, const char* file, const std::uint8_t* data, std::size_t size);

// Writes the input to "input.<extension>" and runs LoadMesh and LoadPointCloud.
void MeshFile(const char* extension, const std::uint8_t* data, std::size_t size);

// Loads the run-time plugins of `folder` (as the programs load theirs).
void LoadPlugins(const char* folder);

}  // namespace hull::fuzz
