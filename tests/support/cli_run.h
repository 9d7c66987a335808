// Runs a program (hullinspect-cli, as a user runs it) through the shell and
// collects what it printed: the one runner of the tests that drive the CLI.
#pragma once

#include <string>
#include <vector>

namespace hull::testing {

struct CliRun {
  int exit_code = -1;  // -1 when the program could not start or did not exit normally
  std::string output;  // stdout and stderr, interleaved as printed
};

// `s` in single quotes for /bin/sh, any single quote inside escaped.
std::string ShellQuote(const std::string& s);

// Runs `program` with `args` (each passed as one argument) and waits for it.
CliRun RunProgram(const std::string& program, const std::vector<std::string>& args);

// The issues' "refused within 10 s" for a command that must not hang or
// allocate its way through a bomb: 10 s, and 60 s in a sanitizer build,
// whose programs run several times slower (a bound against hangs, not a
// speed goal: speed is measured by the benchmarks).
inline double RefusalSeconds() {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  return 60.0;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return 60.0;
#else
  return 10.0;
#endif
#else
  return 10.0;
#endif
}

}  // namespace hull::testing
