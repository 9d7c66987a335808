// Progress on the terminal for long CLI jobs: a single updating line on a
// TTY, a line every few percent otherwise; Ctrl-C requests cancellation.
#pragma once

#include <atomic>
#include <string>

#include "base/progress.h"

namespace hull::cli {

class ConsoleProgress final : public Progress {
 public:
  explicit ConsoleProgress(bool quiet = false);
  ~ConsoleProgress() override;
  void Update(double fraction, const std::string& message) override;
  bool Cancelled() const override;
  // Ends the progress line (prints a newline if one is pending).
  void Finish();

 private:
  bool quiet_;
  bool tty_;
  int last_percent_ = -100;
  bool line_open_ = false;
};

}  // namespace hull::cli
