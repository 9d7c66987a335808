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

#include <unistd.h>

#include "base/error.h"
#include "base/progress.h"
#include "pipeline/pipeline.h"
#include "results/compare_files.h"
#include "results/pipeline_job.h"
#include "ui/report/report.h"
#include "ui/report/report_job.h"
#include "ui/report/results_reader.h"

namespace hull::report {
namespace {

constexpr int kExitOk = 0, kExitFailed = 1, kExitUsage = 2, kExitBadInput = 3, kExitInsufficientData = 4;

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

std::string Native(const QString& path) { return QDir::toNativeSeparators(path).toStdString(); }

ReportInputs DemoReportInputs(const PipelineRun& job, double seconds) {
  ReportInputs report;
  if (job.result.mapping) report.mapping = std::make_shared<const MappingResult>(*job.result.mapping);
  report.bundle_path = job.inputs.bundle_path;
  report.mesh_path = job.inputs.mesh_path;
  report.results_path = job.folder;
  report.bundle = std::make_shared<const SurveyBundle>(job.inputs.bundle);
  report.cad = std::make_shared<const TriangleMesh>(job.inputs.mesh);
  report.pipeline = std::make_shared<const PipelineResult>(job.result);
  report.run_seconds = seconds;
  return report;
}

// The demo survey simulated, run through the pipeline (alignment, the three
// models, mapping: once) and written with its report as one results folder.
int RunDemo(const HeadlessCommand& c) {
  QElapsedTimer total;
  total.start();
  PipelineSource source;
  source.demo = true;
  PipelineOptions options;
  options.compare_models = true;  // the report shows the three models side by side
  // As before the results folder: its parent folders are made when missing.
  const QString parent = QFileInfo(QFileInfo(c.out).absoluteFilePath()).absolutePath();
  if (!QDir().mkpath(parent)) throw std::runtime_error("cannot create the folder " + Native(parent));
  StderrProgress progress("demo: simulation, pipeline and mapping");
  ReportFiles files;
  double report_seconds = 0;
  const PipelineRun job = RunPipelineJob(
      source, options, OutputFolder{Native(c.out), false}, "hullinspect --demo", progress,
      [&](const std::string& tmp, const PipelineRun& run) {
        std::fprintf(stderr, "hullinspect: pipeline and mapping done in %.1f s\n", total.elapsed() / 1000.0);
        Say("hullinspect: %s\n", "writing the report");
        QElapsedTimer t;
        t.start();
        const QDir dir(QString::fromStdString(tmp));
        files =
            WriteReport(DemoReportInputs(run, total.elapsed() / 1000.0), dir.filePath(QStringLiteral("report.html")),
                        dir.filePath(QStringLiteral("report.pdf")), {}, dir.filePath(QStringLiteral("figures")));
        report_seconds = t.elapsed() / 1000.0;
      });
  const QDir out(QString::fromStdString(job.folder));
  const std::string mapping_dir = (std::filesystem::path(job.folder) / "mapping").string();
  std::printf("report:   %s\n          %s (%d pages)\n", Native(out.filePath(QStringLiteral("report.html"))).c_str(),
              Native(out.filePath(QStringLiteral("report.pdf"))).c_str(), files.pdf_pages);
  std::printf("figures:  %s\n", Native(out.filePath(QStringLiteral("figures"))).c_str());
  std::printf("model:    %s/model.ply (per-vertex deviation), model.obj, model.stl\n", mapping_dir.c_str());
  std::printf("objects:  %s/objects.csv, objects.json (%zu objects)\n", mapping_dir.c_str(),
              job.result.mapping ? job.result.mapping->objects.size() : 0);
  std::printf("zones:    %s/zones.csv, zones.json\n", mapping_dir.c_str());
  std::printf("results:  %s (alignment.json, adjustment*/, evaluation.txt, summary.json)\n", job.folder.c_str());
  std::printf("survey:   %s\n", job.inputs.bundle_path.c_str());
  std::printf("time:     report %.1f s, total %.1f s\n", report_seconds, total.elapsed() / 1000.0);
  return kExitOk;
}

int RunReport(const HeadlessCommand& c) {
  QElapsedTimer total;
  total.start();
  StderrProgress progress("report");
  const ReportFiles files = RunFolderReport(
      FolderReportRequest{c.results.toStdString(), c.earlier.toStdString(), OutputFolder{Native(c.out), false}},
      "hullinspect --report", progress);
  std::printf("report:   %s\n          %s (%d pages)\n", Native(files.html).c_str(), Native(files.pdf).c_str(),
              files.pdf_pages);
  std::printf("figures:  %s\n", Native(QFileInfo(files.html).absolutePath() + QStringLiteral("/figures")).c_str());
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

void PrepareHeadless() {
  qputenv("QT_QPA_PLATFORM", "offscreen");
  // Without a session (a batch job, ssh, a container) Qt warns that
  // XDG_RUNTIME_DIR is unset and makes its own: give it the same folder
  // quietly (private to the user, as the specification asks).
  if (qEnvironmentVariableIsEmpty("XDG_RUNTIME_DIR")) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("runtime-" + std::to_string(::getuid()));
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    std::filesystem::permissions(dir, std::filesystem::perms::owner_all, std::filesystem::perm_options::replace, ec);
    if (!ec) qputenv("XDG_RUNTIME_DIR", QByteArray::fromStdString(dir.string()));
  }
}

int RunHeadlessJob(const HeadlessCommand& c) {
  if (!c.error.isEmpty()) {
    std::fprintf(stderr, "hullinspect: %s\n\n%s", qPrintable(c.error), qPrintable(HeadlessUsage()));
    return kExitUsage;
  }
  if (c.help) {
    std::fputs(qPrintable(HeadlessUsage()), stdout);
    return kExitOk;
  }
  // The exit codes hullinspect-cli documents (README, "Exit codes").
  try {
    return c.mode == HeadlessCommand::Mode::kDemo ? RunDemo(c) : RunReport(c);
  } catch (const OptionError& e) {
    std::fprintf(stderr, "hullinspect: %s\n", e.what());
    return kExitUsage;
  } catch (const InputError& e) {
    std::fprintf(stderr, "hullinspect: %s\n", e.what());
    return kExitBadInput;
  } catch (const InsufficientData& e) {
    std::fprintf(stderr, "hullinspect: %s\n", e.what());
    return kExitInsufficientData;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hullinspect: %s\n", e.what());
    return kExitFailed;
  }
}

}  // namespace hull::report
