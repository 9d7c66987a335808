// JobRunner: jobs run off the GUI thread (the event loop keeps turning),
// progress arrives as signals, cancelling and superseding leave the last
// good result, and every exception becomes a failure signal.
#include <QElapsedTimer>
#include <QSignalSpy>
#include <QThread>
#include <QTimer>
#include <atomic>
#include <stdexcept>

#include "base/error.h"
#include "gui_test_support.h"

using namespace hull::ui;

namespace {

// A job that works for `steps` x `ms` milliseconds, reporting progress and
// polling for cancellation between steps.
void Work(hull::Progress& p, int steps, int ms) {
  for (int i = 0; i < steps; ++i) {
    p.ThrowIfCancelled();
    p.Update(static_cast<double>(i) / steps, "step " + std::to_string(i));
    QThread::msleep(static_cast<unsigned long>(ms));
  }
}

}  // namespace

class JobRunnerTest : public QObject {
  Q_OBJECT

 private slots:
  void eventLoopTurnsWhileAJobRuns() {
    JobRunner runner;
    QSignalSpy progress(&runner, &JobRunner::jobProgress);
    QSignalSpy succeeded(&runner, &JobRunner::jobSucceeded);
    int ticks = 0;
    qint64 longest_gap = 0;
    QElapsedTimer since_tick;
    QTimer timer;
    timer.setInterval(10);
    connect(&timer, &QTimer::timeout, [&] {
      if (since_tick.isValid()) longest_gap = std::max(longest_gap, since_tick.elapsed());
      since_tick.restart();
      ++ticks;
    });
    Qt::HANDLE gui_thread = QThread::currentThreadId();
    Qt::HANDLE job_thread = nullptr;
    int result = 0;
    timer.start();
    runner.Run<int>(
        QStringLiteral("work"), QStringLiteral("a long job"),
        [&job_thread](hull::Progress& p) {
          job_thread = QThread::currentThreadId();
          Work(p, 60, 25);  // 1.5 s
          return 42;
        },
        [&result](int& value) { result = value; });
    QVERIFY(runner.IsBusy());
    HI_WAIT_IDLE(&runner, 20000);
    timer.stop();
    QCOMPARE(result, 42);
    QCOMPARE(succeeded.count(), 1);
    QVERIFY(job_thread != nullptr && job_thread != gui_thread);
    // 1.5 s at 10 ms: a GUI thread blocked by the job would see no tick at all.
    QVERIFY2(ticks >= 40, qPrintable(QStringLiteral("only %1 timer ticks during the job").arg(ticks)));
    QVERIFY2(longest_gap < 500, qPrintable(QStringLiteral("the event loop stalled for %1 ms").arg(longest_gap)));
    // Throttled progress: some updates, not one per step necessarily.
    QVERIFY(progress.count() >= 5);
  }

  void cancelKeepsThePreviousResult() {
    JobRunner runner;
    int shown = 0;
    runner.Run<int>(
        QStringLiteral("load"), QStringLiteral("first"), [](hull::Progress&) { return 1; },
        [&shown](int& v) { shown = v; });
    HI_WAIT_IDLE(&runner, 10000);
    QCOMPARE(shown, 1);

    QSignalSpy cancelled(&runner, &JobRunner::jobCancelled);
    QSignalSpy succeeded(&runner, &JobRunner::jobSucceeded);
    QSignalSpy progress(&runner, &JobRunner::jobProgress);
    const JobId id = runner.Run<int>(
        QStringLiteral("load"), QStringLiteral("second"),
        [](hull::Progress& p) {
          Work(p, 400, 10);
          return 2;
        },
        [&shown](int& v) { shown = v; });
    QTRY_VERIFY_WITH_TIMEOUT(progress.count() > 0, 10000);
    runner.Cancel(QStringLiteral("load"));
    HI_WAIT_IDLE(&runner, 10000);
    QCOMPARE(shown, 1);
    QCOMPARE(succeeded.count(), 0);
    QCOMPARE(cancelled.count(), 1);
    QCOMPARE(cancelled.at(0).at(0).value<JobId>(), id);
  }

  void cancelCountsEvenWhenTheWorkIgnoresIt() {
    // A job that never polls (a file reader) still must not change the
    // screen after the user cancelled it.
    JobRunner runner;
    bool applied = false;
    std::atomic<bool> started{false};
    runner.Start(
        QStringLiteral("read"), QStringLiteral("deaf job"),
        [&started](hull::Progress&) {
          started = true;
          QThread::msleep(300);
        },
        [&applied] { applied = true; });
    QTRY_VERIFY_WITH_TIMEOUT(started.load(), 10000);
    runner.CancelAll();
    QSignalSpy cancelled(&runner, &JobRunner::jobCancelled);
    HI_WAIT_IDLE(&runner, 10000);
    QVERIFY(!applied);
    QCOMPARE(cancelled.count(), 1);
  }

  void badInputBecomesAFailureNamingTheFileLineAndColumn() {
    JobRunner runner;
    QSignalSpy failed(&runner, &JobRunner::jobFailed);
    runner.Start(QStringLiteral("open"), QStringLiteral("Open a bundle"), [](hull::Progress&) {
      throw hull::InputError({"/data/survey/nav.csv", 12, 31, "yaw"}, "expected a number, got 'abc'");
    });
    HI_WAIT_IDLE(&runner, 10000);
    QCOMPARE(failed.count(), 1);
    QCOMPARE(failed.at(0).at(2).toString(), QStringLiteral("Open a bundle"));
    const QString message = failed.at(0).at(3).toString();
    QVERIFY2(message.contains(QStringLiteral("nav.csv")) && message.contains(QStringLiteral("line 12")) &&
                 message.contains(QStringLiteral("column 31")) && message.contains(QStringLiteral("yaw")) &&
                 message.contains(QStringLiteral("expected a number")),
             qPrintable(message));
  }

  void everyExceptionIsCaughtAtTheThreadBoundary() {
    JobRunner runner;
    QSignalSpy failed(&runner, &JobRunner::jobFailed);
    runner.Start(QStringLiteral("a"), QStringLiteral("std"), [](hull::Progress&) { throw std::runtime_error("boom"); });
    runner.Start(QStringLiteral("b"), QStringLiteral("option"),
                 [](hull::Progress&) { throw hull::OptionError("sigma1", "must be positive"); });
    runner.Start(QStringLiteral("c"), QStringLiteral("not std"), [](hull::Progress&) { throw 7; });
    runner.Start(
        QStringLiteral("d"), QStringLiteral("continuation"), [](hull::Progress&) {},
        [] { throw std::logic_error("the GUI side failed"); });
    HI_WAIT_IDLE(&runner, 10000);
    QCOMPARE(failed.count(), 4);
    QStringList messages;
    for (const auto& args : failed) messages << args.at(3).toString();
    QVERIFY2(messages.contains(QStringLiteral("boom")), qPrintable(messages.join('|')));
    QVERIFY2(messages.contains(QStringLiteral("option sigma1: must be positive")), qPrintable(messages.join('|')));
    QVERIFY2(messages.contains(QStringLiteral("an unknown error (not a std::exception)")),
             qPrintable(messages.join('|')));
    QVERIFY2(messages.contains(QStringLiteral("the GUI side failed")), qPrintable(messages.join('|')));
  }

  void aNewerJobSupersedesAnOlderOneOfItsKind() {
    JobRunner runner;
    std::atomic<int> running{0}, most_running{0};
    auto job = [&running, &most_running](int value) {
      return [&running, &most_running, value](hull::Progress& p) {
        const int now = ++running;
        int seen = most_running.load();
        while (now > seen && !most_running.compare_exchange_weak(seen, now)) {
        }
        try {
          Work(p, value == 3 ? 5 : 300, 10);
        } catch (...) {
          --running;
          throw;
        }
        --running;
        return value;
      };
    };
    std::vector<int> applied;
    auto apply = [&applied](int& v) { applied.push_back(v); };
    QSignalSpy cancelled(&runner, &JobRunner::jobCancelled);
    QSignalSpy progress(&runner, &JobRunner::jobProgress);
    const JobId first = runner.Run<int>(QStringLiteral("k"), QStringLiteral("1"), job(1), apply);
    QTRY_VERIFY_WITH_TIMEOUT(progress.count() > 0, 10000);
    const JobId second = runner.Run<int>(QStringLiteral("k"), QStringLiteral("2"), job(2), apply);
    const JobId third = runner.Run<int>(QStringLiteral("k"), QStringLiteral("3"), job(3), apply);
    HI_WAIT_IDLE(&runner, 20000);
    QCOMPARE(applied, std::vector<int>{3});
    QCOMPARE(most_running.load(), 1);  // never two of a kind at once
    QList<JobId> ids;
    for (const auto& args : cancelled) ids << args.at(0).value<JobId>();
    QVERIFY(ids.contains(first));
    QVERIFY(ids.contains(second));  // replaced while waiting: never started
    QVERIFY(!ids.contains(third));
  }

  void jobsOfDifferentKindsRunTogether() {
    JobRunner runner;
    std::atomic<bool> a_running{false}, b_running{false};
    std::atomic<bool> a_saw_b{false}, b_saw_a{false};
    auto job = [](std::atomic<bool>& me, std::atomic<bool>& other, std::atomic<bool>& saw) {
      return [&me, &other, &saw](hull::Progress&) {
        me = true;
        for (int i = 0; i < 400 && !saw; ++i) {
          if (other) saw = true;
          QThread::msleep(5);
        }
      };
    };
    runner.Start(QStringLiteral("a"), QStringLiteral("a"), job(a_running, b_running, a_saw_b));
    runner.Start(QStringLiteral("b"), QStringLiteral("b"), job(b_running, a_running, b_saw_a));
    HI_WAIT_IDLE(&runner, 10000);
    QVERIFY(a_saw_b && b_saw_a);
  }

  void destroyingTheRunnerCancelsAndWaits() {
    std::atomic<bool> started{false}, saw_cancel{false};
    bool applied = false;
    {
      JobRunner runner;
      runner.Start(
          QStringLiteral("long"), QStringLiteral("long"),
          [&](hull::Progress& p) {
            started = true;
            for (int i = 0; i < 1000; ++i) {
              if (p.Cancelled()) {
                saw_cancel = true;
                return;
              }
              QThread::msleep(5);
            }
          },
          [&applied] { applied = true; });
      QTRY_VERIFY_WITH_TIMEOUT(started.load(), 10000);
    }
    QVERIFY(saw_cancel.load());
    QVERIFY(!applied);
  }

  void busyChangesOnceForABatch() {
    JobRunner runner;
    QSignalSpy busy(&runner, &JobRunner::busyChanged);
    runner.Start(QStringLiteral("x"), QStringLiteral("x"), [](hull::Progress& p) { Work(p, 5, 5); });
    runner.Start(QStringLiteral("y"), QStringLiteral("y"), [](hull::Progress& p) { Work(p, 5, 5); });
    HI_WAIT_IDLE(&runner, 10000);
    QCOMPARE(busy.count(), 2);
    QCOMPARE(busy.at(0).at(0).toBool(), true);
    QCOMPARE(busy.at(1).at(0).toBool(), false);
  }
};

HI_GUI_TEST_MAIN(JobRunnerTest)
#include "job_runner_test.moc"
