#include "ui/report/headless_job.h"

#include <QDir>
#include <QElapsedTimer>
#include <QFileInfo>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "base/progress.h"
#include "mapping/mapper.h"
#include "mapping/survey_compare.h"
#include "pipeline/pipeline.h"
#include "simulate/survey_simulator.h"
#include "ui/report/report.h"
#include "ui/report/results_reader.h"

namespace hull::report {
namespace {

constexpr int kExitOk = 0, kExitFailed = 1, kExitUsage = 2;

// Progress on stderr: a line per new message, or per 10 % of the same one.
class StderrProgress final : public Progress {
 public:
  explicit StderrProgress(const char* step) : step_(step) {}
  void Update(double fraction, const std::string& message) override {
    const int tenth = static_cast<int>(fraction * 10);
    if (message == last_ && tenth == last_tenth_) return;
    last_ = message;
    last_tenth_ = tenth;
    std::fprintf(stderr, "hullinspect: %s [%3.0f %%] %s\n", step_, 100 * fraction, message.c_str());
  }
  bool Cancelled() const override { return false; }

 private:
  const char* step_;
  std::string last_;
  int last_tenth_ = -1;
};

void Say(const char* format, const std::string& what) { std::fprintf(stderr, format, what.c_str()); }

struct Step {
  std::string name;
  double seconds = 0;
};

std::string Native(const QString& path) { return QDir::toNativeSeparators(path).toStdString(); }

int RunDemo(const HeadlessCommand& c) {
  QElapsedTimer total;
  total.start();
  std::vector<Step> steps;
  const auto timed = [&](const char* name, auto&& work) {
    QElapsedTimer t;
    t.start();
    work();
    steps.push_back({name, t.elapsed() / 1000.0});
    std::fprintf(stderr, "hullinspect: %s done in %.1f s\n", name, steps.back().seconds);
  };
  if (!QDir().mkpath(c.out)) throw std::runtime_error("cannot create the folder " + Native(c.out));
  const QDir out(QFileInfo(c.out).absoluteFilePath());
  const std::string out_dir = out.absolutePath().toStdString();
  const std::string bundle_dir = (std::filesystem::path(out_dir) / "demo-survey").string();

  timed("simulation", [&] {
    StderrProgress p("simulating the demo survey");
    WriteSimulatedSurvey(SimulateSurvey(SurveyPreset("demo"), p), bundle_dir);
  });
  PipelineInputs in;
  auto result = std::make_shared<PipelineResult>();
  timed("pipeline", [&] {
    in = LoadPipelineInputs(bundle_dir);
    PipelineOptions options;
    options.compare_models = true;  // the report shows the three models side by side
    StderrProgress p("pipeline");
    *result = RunPipeline(in, options, p);
    WritePipelineResult(in, *result, out_dir);
  });

  auto mapping = std::make_shared<MappingResult>();
  const std::string mapping_dir = (std::filesystem::path(out_dir) / "mapping").string();
  timed("mapping", [&] {
    StderrProgress p("mapping");
    *mapping = RunMapping(MappingInputFromAdjustment(result->adjustment, in.bundle), in.mesh, MappingOptions{}, p);
    mapping->inputs = {{"adjustment", (std::filesystem::path(out_dir) / "adjustment").string()},
                       {"bundle", in.bundle_path},
                       {"mesh", in.mesh_path}};
    WriteMappingResult(*mapping, mapping_dir);
  });

  ReportInputs report;
  report.mapping = mapping;
  report.bundle_path = in.bundle_path;
  report.mesh_path = in.mesh_path;
  report.results_path = out_dir;
  report.bundle = std::make_shared<const SurveyBundle>(std::move(in.bundle));
  report.cad = std::make_shared<const TriangleMesh>(std::move(in.mesh));
  report.pipeline = result;
  report.run_seconds = total.elapsed() / 1000.0;

  ReportFiles files;
  timed("report", [&] {
    Say("hullinspect: %s\n", "writing the report");
    files = WriteReport(report, out.filePath(QStringLiteral("report.html")), out.filePath(QStringLiteral("report.pdf")),
                        {}, out.filePath(QStringLiteral("figures")));
  });

  std::printf("report:   %s\n          %s (%d pages)\n", Native(files.html).c_str(), Native(files.pdf).c_str(),
              files.pdf_pages);
  std::printf("figures:  %s\n", Native(out.filePath(QStringLiteral("figures"))).c_str());
  std::printf("model:    %s/model.ply (per-vertex deviation), model.obj, model.stl\n", mapping_dir.c_str());
  std::printf("objects:  %s/objects.csv, objects.json (%zu objects)\n", mapping_dir.c_str(), mapping->objects.size());
  std::printf("zones:    %s/zones.csv, zones.json\n", mapping_dir.c_str());
  std::printf("results:  %s (alignment.json, adjustment*/, evaluation.txt, summary.json)\n", out_dir.c_str());
  std::printf("survey:   %s\n", bundle_dir.c_str());
  std::printf("time:     ");
  for (const Step& s : steps) std::printf("%s %.1f s, ", s.name.c_str(), s.seconds);
  std::printf("total %.1f s\n", total.elapsed() / 1000.0);
  return kExitOk;
}

int RunReport(const HeadlessCommand& c) {
  QElapsedTimer total;
  total.start();
  Say("hullinspect: reading the results in %s\n", Native(c.results));
  ReportInputs inputs = ReadReportInputs(c.results.toStdString());
  if (!c.earlier.isEmpty()) {
    StderrProgress p("comparing with the earlier survey");
    inputs.comparison = std::make_shared<const SurveyComparisonRun>(RunSurveyComparison(
        c.earlier.toStdString(), c.results.toStdString(), inputs.mesh_path, 1.0, SurveyCompareOptions{}, p));
  }
  const QDir out(QFileInfo(c.out).absoluteFilePath());
  Say("hullinspect: %s\n", "writing the report");
  const ReportFiles files =
      WriteReport(inputs, out.filePath(QStringLiteral("report.html")), out.filePath(QStringLiteral("report.pdf")), {},
                  out.filePath(QStringLiteral("figures")));
  std::printf("report:   %s\n          %s (%d pages)\n", Native(files.html).c_str(), Native(files.pdf).c_str(),
              files.pdf_pages);
  std::printf("figures:  %s\n", Native(out.filePath(QStringLiteral("figures"))).c_str());
  std::printf("time:     %.1f s\n", total.elapsed() / 1000.0);
  return kExitOk;
}

}  // namespace

bool IsBatchCommand(const QStringList& a) {
  return a.contains(QStringLiteral("--report")) ||
         (a.contains(QStringLiteral("--demo")) && a.contains(QStringLiteral("--out")));
}

HeadlessCommand ParseHeadlessCommand(const QStringList& a) {
  HeadlessCommand c;
  for (int i = 0; i < a.size(); ++i) {
    const QString& arg = a[i];
    const auto value = [&](QString& into) {
      if (i + 1 >= a.size() || a[i + 1].startsWith(QStringLiteral("--"))) {
        c.error = QStringLiteral("%1 needs a folder").arg(arg);
        return;
      }
      into = a[++i];
    };
    if (arg == QLatin1String("--demo")) {
      c.mode = c.mode == HeadlessCommand::Mode::kReport ? HeadlessCommand::Mode::kNone : HeadlessCommand::Mode::kDemo;
      if (c.mode == HeadlessCommand::Mode::kNone) c.error = QStringLiteral("give --demo or --report, not both");
    } else if (arg == QLatin1String("--report")) {
      if (c.mode == HeadlessCommand::Mode::kDemo) c.error = QStringLiteral("give --demo or --report, not both");
      c.mode = HeadlessCommand::Mode::kReport;
      value(c.results);
    } else if (arg == QLatin1String("--out")) {
      value(c.out);
    } else if (arg == QLatin1String("--compare-with")) {
      value(c.earlier);
    } else if (arg == QLatin1String("--help") || arg == QLatin1String("-h")) {
      c.help = true;
    } else {
      c.error = QStringLiteral(
                    "the headless job takes --demo [--out DIR] or --report RESULTS [--compare-with EARLIER] --out DIR, "
                    "not '%1'")
                    .arg(arg);
    }
    if (!c.error.isEmpty()) return c;
  }
  if (c.help) return c;
  if (c.mode == HeadlessCommand::Mode::kNone) {
    c.error = QStringLiteral("nothing to do: give --demo or --report RESULTS");
  } else if (c.mode == HeadlessCommand::Mode::kReport && c.out.isEmpty()) {
    c.error = QStringLiteral("--report needs --out DIR");
  } else if (c.mode != HeadlessCommand::Mode::kReport && !c.earlier.isEmpty()) {
    c.error = QStringLiteral("--compare-with goes with --report");
  } else if (c.out.isEmpty()) {
    c.out = QStringLiteral("demo-output");
  }
  return c;
}

QString HeadlessUsage() {
  return QStringLiteral(
      "usage: hullinspect --demo [--out DIR]\n"
      "       hullinspect --report RESULTS [--compare-with EARLIER] --out DIR\n"
      "\n"
      "Without a display (no DISPLAY or WAYLAND_DISPLAY) hullinspect runs its main job headless:\n"
      "  --demo          simulate the demo survey into DIR/demo-survey, run the whole pipeline on it\n"
      "                  (alignment, the three surface models, mapping) and write the results and the\n"
      "                  report (report.html, report.pdf, figures/) into DIR (default ./demo-output)\n"
      "  --report RESULTS  write the report again from a results folder of --demo or hullinspect-cli\n"
      "  --compare-with EARLIER  with --report: add the change since an earlier survey's results folder\n"
      "                  (both mapped against the same CAD mesh; see hullinspect-cli compare)\n"
      "  --out DIR       the output folder\n"
      "The batch front end is hullinspect-cli (e.g. hullinspect-cli run --demo --out DIR).\n");
}

void PrepareHeadless() { qputenv("QT_QPA_PLATFORM", "offscreen"); }

int RunHeadlessJob(const HeadlessCommand& c) {
  if (!c.error.isEmpty()) {
    std::fprintf(stderr, "hullinspect: %s\n\n%s", qPrintable(c.error), qPrintable(HeadlessUsage()));
    return kExitUsage;
  }
  if (c.help) {
    std::fputs(qPrintable(HeadlessUsage()), stdout);
    return kExitOk;
  }
  try {
    return c.mode == HeadlessCommand::Mode::kDemo ? RunDemo(c) : RunReport(c);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hullinspect: %s\n", e.what());
    return kExitFailed;
  }
}

}  // namespace hull::report
