#include "cli/console_progress.h"

#include <unistd.h>

#include <csignal>
#include <cstdio>

namespace hull::cli {
namespace {
std::atomic<bool> g_interrupted{false};
extern "C" void OnSigint(int) { g_interrupted.store(true); }
}  // namespace

ConsoleProgress::ConsoleProgress(bool quiet) : quiet_(quiet), tty_(::isatty(2) != 0) { std::signal(SIGINT, OnSigint); }

ConsoleProgress::~ConsoleProgress() { Finish(); }

void ConsoleProgress::Update(double fraction, const std::string& message) {
  if (quiet_) return;
  const int percent = static_cast<int>(fraction * 100.0 + 0.5);
  if (tty_) {
    std::fprintf(stderr, "\r[%3d%%] %-70.70s", percent, message.c_str());
    std::fflush(stderr);
    line_open_ = true;
  } else if (percent >= last_percent_ + 10 || percent == 100) {
    std::fprintf(stderr, "[%3d%%] %s\n", percent, message.c_str());
    last_percent_ = percent;
  }
}

bool ConsoleProgress::Cancelled() const { return g_interrupted.load(); }

void ConsoleProgress::Finish() {
  if (line_open_) std::fprintf(stderr, "\n");
  line_open_ = false;
}

}  // namespace hull::cli
