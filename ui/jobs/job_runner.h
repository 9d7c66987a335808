// Runs Qt-free jobs (std::function<void(hull::Progress&)>) in worker threads
// (COLMAP's ControllerThread): progress arrives as queued signals, Cancel
// sets the job's flag, and every exception is caught at the thread boundary
// and reported as a failure signal, so a worker never ends the program.
//
// Jobs have a kind ("open", "export", later "adjust", "map"). At most one job
// of a kind runs at a time: a newer request of the same kind cancels the
// running one and starts as soon as it has stopped (a request still waiting
// for that is replaced). A job's result reaches the GUI only through its
// on_success continuation, which runs on the GUI thread and only when the
// job returned normally, was not cancelled and was not superseded; a
// cancelled or failed job therefore leaves the last good result on screen.
#pragma once

#include <QObject>
#include <QString>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <utility>

#include "base/progress.h"

namespace hull::ui {

using JobFunction = std::function<void(hull::Progress&)>;
using JobId = quint64;

class JobRunner : public QObject {
  Q_OBJECT

 public:
  explicit JobRunner(QObject* parent = nullptr);
  // Cancels every job and waits for the worker threads to stop.
  ~JobRunner() override;

  // Queues `work` as the job of `kind` (see above); `title` names it in the
  // status bar and in failure messages. Returns the job's id.
  JobId Start(const QString& kind, const QString& title, JobFunction work, std::function<void()> on_success = {});

  // A job computing a value of type T in the worker, handed to `apply` on
  // the GUI thread when the job succeeds.
  template <typename T>
  JobId Run(const QString& kind, const QString& title, std::function<T(hull::Progress&)> compute,
            std::function<void(T&)> apply) {
    auto result = std::make_shared<std::optional<T>>();
    return Start(
        kind, title, [result, compute = std::move(compute)](hull::Progress& p) { result->emplace(compute(p)); },
        [result, apply = std::move(apply)] { apply(**result); });
  }

  // Cancels the running and the waiting job of a kind (no-op when idle).
  void Cancel(const QString& kind);
  void CancelAll();

  bool IsBusy() const;
  bool IsBusy(const QString& kind) const;

 signals:
  void jobStarted(hull::ui::JobId id, const QString& kind, const QString& title);
  // fraction in [0, 1]; updates are throttled to about 25 per second.
  void jobProgress(hull::ui::JobId id, const QString& kind, double fraction, const QString& message);
  void jobSucceeded(hull::ui::JobId id, const QString& kind);
  // message describes the error (for bad input: file, line, column, field).
  void jobFailed(hull::ui::JobId id, const QString& kind, const QString& title, const QString& message);
  // Cancelled by the user or superseded by a newer job of the same kind
  // (also emitted for a waiting job that was replaced before it started).
  void jobCancelled(hull::ui::JobId id, const QString& kind);
  // True when the first job starts, false when the last one ends.
  void busyChanged(bool busy);

 private:
  struct Job;
  struct KindState {
    std::shared_ptr<Job> running;
    std::shared_ptr<Job> waiting;
  };

  void Launch(const std::shared_ptr<Job>& job);
  void OnThreadFinished(const std::shared_ptr<Job>& job);
  void UpdateBusy();

  std::map<QString, KindState> kinds_;
  JobId next_id_ = 1;
  bool busy_ = false;
};

}  // namespace hull::ui
