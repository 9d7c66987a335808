// bench_gui_stall: does the GUI thread keep turning while hullinspect works?
//
//   xvfb-run -a -s "-screen 0 1280x1024x24" build/bin/bench_gui_stall [--details]
//
// Opens the main window on the demo survey and does what an inspector does:
// run the inspection (alignment, adjustment, mapping), change sigma (a warm
// re-adjustment, then mapping), change tau (mapping only), undo both (cached
// results), compare the surface models, move the cross-section slab, select
// detected objects (the 3-D view flies there) and play the sonar demo. A
// 1 ms timer measures the event loop: a stall is the time between two of its
// ticks beyond the interval. Every event dispatch that takes longer than
// 20 ms is recorded with its receiver and type (--details prints them), to
// say where a stall comes from. The goal: the longest stall under 100 ms.
#include <QAction>
#include <QApplication>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QPointer>
#include <QTableView>
#include <QTimer>
#include <QUndoStack>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "ui/app/app_setup.h"
#include "ui/app/main_window.h"
#include "ui/jobs/job_runner.h"
#include "ui/panels/objects_panel.h"
#include "ui/panels/parameter_panel.h"
#include "ui/panels/sonar_panel.h"
#include "ui/views/cross_section_view.h"

namespace {

struct SlowEvent {
  double ms = 0;
  std::string what;
};

// Times every top-level event dispatch of the GUI thread.
class TimedApplication : public QApplication {
 public:
  TimedApplication(int& argc, char** argv) : QApplication(argc, argv) {}
  bool notify(QObject* receiver, QEvent* event) override {
    if (depth_++ > 0) {
      const bool r = QApplication::notify(receiver, event);
      --depth_;
      return r;
    }
    // The receiver may be gone afterwards (a single-shot timer deletes
    // itself): note what it is first.
    const char* class_name = receiver->metaObject()->className();
    const int type = static_cast<int>(event->type());
    QPointer<QObject> alive(receiver);
    QElapsedTimer t;
    t.start();
    const bool r = QApplication::notify(receiver, event);
    --depth_;
    const double ms = t.nsecsElapsed() / 1e6;
    if (ms > 20.0) {
      std::string what = class_name;
      if (alive && !alive->objectName().isEmpty()) what += " '" + alive->objectName().toStdString() + "'";
      what += " event " + std::to_string(type);
      slow.push_back({ms, what});
    }
    return r;
  }
  std::vector<SlowEvent> slow;

 private:
  int depth_ = 0;
};

// The gaps between the ticks of a 1 ms timer.
class StallMeter {
 public:
  StallMeter() {
    timer_.setTimerType(Qt::PreciseTimer);
    timer_.setInterval(1);
    QObject::connect(&timer_, &QTimer::timeout, [this] {
      const double now = clock_.nsecsElapsed() / 1e6;
      if (last_ >= 0) longest_ = std::max(longest_, now - last_ - 1.0);
      last_ = now;
    });
    clock_.start();
    timer_.start();
  }
  // The longest stall since the last call (ms).
  double Take() {
    const double l = longest_;
    longest_ = 0;
    return l;
  }

 private:
  QTimer timer_;
  QElapsedTimer clock_;
  double last_ = -1, longest_ = 0;
};

void Wait(int ms) {
  QEventLoop loop;
  QTimer::singleShot(ms, &loop, &QEventLoop::quit);
  loop.exec();
}

// Turns the event loop until no job runs, then a little longer (renders).
void WaitIdle(hull::ui::JobRunner* jobs) {
  Wait(50);
  while (jobs->IsBusy()) {
    QEventLoop loop;
    QObject::connect(jobs, &hull::ui::JobRunner::busyChanged, &loop, [&](bool busy) {
      if (!busy) loop.quit();
    });
    if (jobs->IsBusy()) loop.exec();
  }
  Wait(300);
}

}  // namespace

int main(int argc, char** argv) {
  const bool details = argc > 1 && std::strcmp(argv[1], "--details") == 0;
  if (!hull::ui::HasDisplay()) {
    std::fprintf(stderr, "bench_gui_stall needs a display: run it under xvfb-run -a\n");
    return 2;
  }
  hull::ui::PrepareApplication();
  TimedApplication app(argc, argv);
  hull::ui::InitApplication();
  hull::ui::MainWindow w;
  w.SetErrorSink([](const QString& title, const QString& message) {
    std::fprintf(stderr, "error: %s: %s\n", qPrintable(title), qPrintable(message));
  });
  w.resize(1280, 900);
  w.show();
  Wait(500);

  StallMeter meter;
  struct Row {
    std::string stage;
    double seconds, stall_ms;
    std::string slowest;
  };
  std::vector<Row> rows;
  auto stage = [&](const char* name, const std::function<void()>& act) {
    app.slow.clear();
    meter.Take();
    QElapsedTimer t;
    t.start();
    act();
    WaitIdle(w.jobs());
    Row r{name, t.elapsed() / 1000.0, meter.Take(), ""};
    auto worst = std::max_element(app.slow.begin(), app.slow.end(),
                                  [](const SlowEvent& a, const SlowEvent& b) { return a.ms < b.ms; });
    if (worst != app.slow.end()) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.0f ms: ", worst->ms);
      r.slowest = buf + worst->what;
    }
    if (details) {
      for (const SlowEvent& e : app.slow) std::printf("  [%s] %.1f ms %s\n", name, e.ms, e.what.c_str());
    }
    rows.push_back(r);
  };
  auto real = [&](const char* key) {
    return qobject_cast<QDoubleSpinBox*>(w.parameterPanel()->editor(QString::fromLatin1(key)));
  };

  stage("open the demo", [&] { w.OpenDemo(); });
  stage("run: alignment, adjustment, mapping", [&] { w.action(QStringLiteral("runInspection"))->trigger(); });
  stage("sigma1 0.02 -> 0.03: warm re-adjustment, mapping", [&] { real("sigma1")->setValue(0.03); });
  stage("tau 0 -> 0.06: mapping only", [&] { real("tau")->setValue(0.06); });
  stage("undo twice: cached results", [&] {
    w.parameterPanel()->undoStack()->undo();
    Wait(100);
    w.parameterPanel()->undoStack()->undo();
  });
  stage("compare models", [&] { w.action(QStringLiteral("compareModels"))->trigger(); });
  stage("move the slab (10 positions)", [&] {
    hull::ui::SlabSpec s = w.crossSectionView()->slab();
    const auto [lo, hi] = w.crossSectionView()->positionRange();
    for (int i = 0; i < 10; ++i) {
      s.position = lo + (hi - lo) * i / 9.0;
      w.crossSectionView()->SetSlab(s);
      Wait(30);
    }
  });
  stage("select objects (the view flies there)", [&] {
    QTableView* table = w.objectsPanel()->objectsTable();
    for (int row = 0; row < std::min(4, table->model()->rowCount()); ++row) {
      table->setCurrentIndex(table->model()->index(row, 0));
      Wait(400);
    }
  });
  stage("sonar demo: run and play", [&] {
    w.action(QStringLiteral("openSonarDemoPrism"))->trigger();
    WaitIdle(w.jobs());
    w.sonarPanel()->Play();
    QElapsedTimer t;
    t.start();
    while (w.sonarPanel()->playing() && t.elapsed() < 30000) Wait(50);
  });

  std::printf("| %-48s | %7s | %9s | %s\n", "stage", "wall s", "stall ms", "slowest dispatch");
  std::printf("|%s|--------:|----------:|---\n", std::string(50, '-').c_str());
  double longest = 0;
  for (const Row& r : rows) {
    std::printf("| %-48s | %7.2f | %9.1f | %s\n", r.stage.c_str(), r.seconds, r.stall_ms, r.slowest.c_str());
    longest = std::max(longest, r.stall_ms);
  }
  std::printf("\nlongest event-loop stall: %.1f ms (goal: under 100 ms)\n", longest);
  return 0;
}
