// Shared by the libFuzzer harnesses (tests/fuzz): a scratch folder per
// process and the one rule of every harness — a reader may refuse its input
// only with hull::InputError; any other exception, a crash, a sanitizer
// report, a leak or a hang is a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace hull::fuzz {

// A fresh folder under $TMPDIR (or /tmp) for this process, removed at exit.
const std::string& ScratchDir();

// Copies the folder `from` (recursively) to `to`, replacing what is there.
void CopyTree(const std::string& from, const std::string& to);

// Writes the fuzzer's bytes to `path` (truncating).
void WriteInput(const std::string& path, const std::uint8_t* data, std::size_t size);

inline std::string_view AsText(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// Runs `body`, swallowing hull::InputError (the expected refusal); anything
// else propagates, so libFuzzer reports it as a crash with the exception.
template <typename Body>
void ExpectOnlyInputError(Body body);

}  // namespace hull::fuzz

#include "base/error.h"

template <typename Body>
void hull::fuzz::ExpectOnlyInputError(Body body) {
  try {
    body();
  } catch (const hull::InputError&) {
  }
}
