// Progress reporting and cancellation for long jobs (CCCoreLib's
// GenericProgressCallback). Qt-free: the ui/ layer wraps it in queued signals.
#pragma once

#include <atomic>
#include <functional>
#include <string>

namespace hull {

class Progress {
 public:
  virtual ~Progress() = default;
  // fraction in [0, 1] of the whole job; message says what is being done.
  virtual void Update(double fraction, const std::string& message) = 0;
  // True once the user asked to stop; jobs poll it between units of work.
  virtual bool Cancelled() const = 0;
  // Throws hull::Cancelled when Cancelled() is true.
  void ThrowIfCancelled() const;
};

// Discards updates and is never cancelled.
class NullProgress final : public Progress {
 public:
  void Update(double, const std::string&) override {}
  bool Cancelled() const override { return false; }
};

// Forwards to a callback; cancellation through an atomic flag another thread sets.
class CallbackProgress final : public Progress {
 public:
  using Callback = std::function<void(double, const std::string&)>;
  explicit CallbackProgress(Callback cb = {}) : cb_(std::move(cb)) {}
  void Update(double fraction, const std::string& message) override {
    if (cb_) cb_(fraction, message);
  }
  bool Cancelled() const override { return cancel_.load(std::memory_order_relaxed); }
  void RequestCancel() { cancel_.store(true, std::memory_order_relaxed); }

 private:
  Callback cb_;
  std::atomic<bool> cancel_{false};
};

// Maps a sub-job's [0, 1] onto [begin, end] of its parent.
class SubProgress final : public Progress {
 public:
  SubProgress(Progress& parent, double begin, double end) : parent_(parent), begin_(begin), end_(end) {}
  void Update(double fraction, const std::string& message) override {
    parent_.Update(begin_ + (end_ - begin_) * fraction, message);
  }
  bool Cancelled() const override { return parent_.Cancelled(); }

 private:
  Progress& parent_;
  double begin_, end_;
};

}  // namespace hull
