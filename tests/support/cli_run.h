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

}  // namespace hull::testing
