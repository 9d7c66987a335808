#include "ui/jobs/job_runner.h"

#include <QThread>
#include <atomic>
#include <chrono>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "base/error.h"
#include "ui/jobs/error_text.h"

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace hull::ui {

struct JobRunner::Job {
  enum class Outcome { kSucceeded, kFailed, kCancelled };

  JobId id = 0;
  QString kind, title;
  JobFunction work;
  std::function<void()> on_success;
  std::atomic<bool> cancel{false};
  // Written by the worker, read on the GUI thread after QThread::finished.
  Outcome outcome = Outcome::kCancelled;
  QString error;
  QThread* thread = nullptr;
};

namespace {

// Jobs run at a lower CPU priority than the GUI thread (nice +10, per thread
// on Linux; the threads a job starts -- Ceres', TBB's -- inherit it): on a
// machine whose cores the job keeps busy, the event loop and the rendering
// still get their turn at once.
void LowerThisThreadsPriority() {
#ifdef __linux__
  const auto tid = static_cast<id_t>(syscall(SYS_gettid));
  setpriority(PRIO_PROCESS, tid, 10);
#endif
}

// The job's view of hull::Progress: updates become JobRunner::jobProgress
// signals (queued to receivers on the GUI thread), at most one per 40 ms
// unless the message changes; Cancelled() reads the job's flag. Thread-safe:
// a job may report from several worker threads (e.g. a TBB loop).
class JobProgress final : public hull::Progress {
 public:
  using Emit = std::function<void(double, const QString&)>;
  JobProgress(Emit send, const std::atomic<bool>& cancel) : emit_(std::move(send)), cancel_(cancel) {}

  void Update(double fraction, const std::string& message) override {
    if (Cancelled()) return;
    const auto now = std::chrono::steady_clock::now();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (message == last_message_ && now - last_sent_ < std::chrono::milliseconds(40)) return;
      last_sent_ = now;
      last_message_ = message;
    }
    emit_(fraction < 0 ? 0.0 : (fraction > 1 ? 1.0 : fraction), QString::fromStdString(message));
  }
  bool Cancelled() const override { return cancel_.load(std::memory_order_relaxed); }

 private:
  Emit emit_;
  const std::atomic<bool>& cancel_;
  std::mutex mutex_;
  std::string last_message_;
  std::chrono::steady_clock::time_point last_sent_{};
};

}  // namespace

JobRunner::JobRunner(QObject* parent) : QObject(parent) {
  // jobProgress crosses threads: its argument types must be known to queue it.
  qRegisterMetaType<JobId>("hull::ui::JobId");
}

JobRunner::~JobRunner() {
  std::vector<std::shared_ptr<Job>> running;
  for (auto& [kind, state] : kinds_) {
    state.waiting.reset();
    if (state.running) {
      state.running->cancel = true;
      running.push_back(state.running);
    }
  }
  for (const auto& job : running) {
    if (!job->thread) continue;
    job->thread->disconnect(this);
    job->thread->wait();
    delete job->thread;
    job->thread = nullptr;
  }
}

JobId JobRunner::Start(const QString& kind, const QString& title, JobFunction work, std::function<void()> on_success) {
  auto job = std::make_shared<Job>();
  job->id = next_id_++;
  job->kind = kind;
  job->title = title;
  job->work = std::move(work);
  job->on_success = std::move(on_success);

  KindState& state = kinds_[kind];
  std::shared_ptr<Job> replaced = std::move(state.waiting);
  state.waiting.reset();
  if (state.running) {
    state.running->cancel = true;  // it reports jobCancelled when its thread ends
    state.waiting = job;
  } else {
    state.running = job;
  }
  if (replaced) emit jobCancelled(replaced->id, kind);
  if (state.running == job) Launch(job);
  UpdateBusy();
  return job->id;
}

void JobRunner::Launch(const std::shared_ptr<Job>& job) {
  Job* raw = job.get();
  JobProgress::Emit emit_progress = [this, id = job->id, kind = job->kind](double f, const QString& message) {
    emit jobProgress(id, kind, f, message);  // from the worker: queued to GUI-thread receivers
  };
  job->thread = QThread::create([raw, emit_progress] {
    LowerThisThreadsPriority();
    JobProgress progress(emit_progress, raw->cancel);
    try {
      raw->work(progress);
      raw->outcome = Job::Outcome::kSucceeded;
    } catch (const hull::Cancelled&) {
      raw->outcome = Job::Outcome::kCancelled;
    } catch (...) {
      raw->error = DescribeException(std::current_exception());
      raw->outcome = Job::Outcome::kFailed;
    }
    raw->work = nullptr;  // release what the job captured while still in the worker
  });
  job->thread->setObjectName(QStringLiteral("job:") + job->kind);
  connect(job->thread, &QThread::finished, this, [this, job] { OnThreadFinished(job); });
  emit jobStarted(job->id, job->kind, job->title);
  job->thread->start();
}

void JobRunner::OnThreadFinished(const std::shared_ptr<Job>& job) {
  job->thread->deleteLater();
  job->thread = nullptr;
  KindState& state = kinds_[job->kind];
  if (state.running == job) state.running.reset();

  // A flag raised after the work returned still counts: the user asked for
  // nothing to change, or a newer job of this kind replaces this one.
  Job::Outcome outcome = job->outcome;
  if (job->cancel.load() && outcome == Job::Outcome::kSucceeded) outcome = Job::Outcome::kCancelled;
  QString error = job->error;
  if (outcome == Job::Outcome::kSucceeded && job->on_success) {
    try {
      job->on_success();
    } catch (...) {
      outcome = Job::Outcome::kFailed;
      error = DescribeException(std::current_exception());
    }
  }
  job->on_success = nullptr;

  // Start the waiting job before reporting, so that handlers see a
  // consistent state (and may queue further jobs of this kind).
  if (!state.running && state.waiting) {
    state.running = std::move(state.waiting);
    state.waiting.reset();
    Launch(state.running);
  }
  switch (outcome) {
    case Job::Outcome::kSucceeded:
      emit jobSucceeded(job->id, job->kind);
      break;
    case Job::Outcome::kFailed:
      emit jobFailed(job->id, job->kind, job->title, error);
      break;
    case Job::Outcome::kCancelled:
      emit jobCancelled(job->id, job->kind);
      break;
  }
  UpdateBusy();
}

void JobRunner::Cancel(const QString& kind) {
  auto it = kinds_.find(kind);
  if (it == kinds_.end()) return;
  std::shared_ptr<Job> dropped = std::move(it->second.waiting);
  it->second.waiting.reset();
  if (it->second.running) it->second.running->cancel = true;
  if (dropped) emit jobCancelled(dropped->id, kind);
  UpdateBusy();
}

void JobRunner::CancelAll() {
  std::vector<QString> kinds;
  for (const auto& [kind, state] : kinds_) kinds.push_back(kind);
  for (const QString& kind : kinds) Cancel(kind);
}

bool JobRunner::IsBusy() const {
  for (const auto& [kind, state] : kinds_) {
    if (state.running || state.waiting) return true;
  }
  return false;
}

bool JobRunner::IsBusy(const QString& kind) const {
  auto it = kinds_.find(kind);
  return it != kinds_.end() && (it->second.running || it->second.waiting);
}

void JobRunner::UpdateBusy() {
  const bool busy = IsBusy();
  if (busy == busy_) return;
  busy_ = busy;
  emit busyChanged(busy);
}

}  // namespace hull::ui
