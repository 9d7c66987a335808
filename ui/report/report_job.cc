#include "ui/report/report_job.h"

#include <QDir>
#include <QFileInfo>
#include <QString>
#include <filesystem>
#include <memory>

#include "base/error.h"
#include "results/compare_files.h"
#include "results/pipeline_files.h"
#include "results/sonar_files.h"
#include "ui/report/results_reader.h"

namespace hull::report {
namespace fs = std::filesystem;
namespace {

bool HasFile(const fs::path& dir, const char* name) {
  std::error_code ec;
  return fs::is_regular_file(dir / name, ec);
}

// The pipeline results that hold `dir`: itself, or the folder above a
// pipeline's mapping/ ("" : neither).
std::string PipelineFolderOf(const std::string& dir) {
  const fs::path p = fs::absolute(dir).lexically_normal();
  if (HasFile(p, "summary.json") && !IsSonarResults(p.string())) return p.string();
  const fs::path up = p.filename().empty() ? p.parent_path().parent_path() : p.parent_path();
  if (HasFile(p, "mapping.json") && HasFile(up, "summary.json") && !IsSonarResults(up.string())) return up.string();
  return "";
}

// a == b or a lies inside b.
bool Within(const fs::path& a, const fs::path& b) {
  const fs::path ra = fs::weakly_canonical(fs::absolute(a)), rb = fs::weakly_canonical(fs::absolute(b));
  auto ia = ra.begin();
  for (auto ib = rb.begin(); ib != rb.end(); ++ib, ++ia) {
    if (ib->empty()) continue;  // a trailing separator
    if (ia == ra.end() || *ia != *ib) return false;
  }
  return true;
}

ReportInputs ComparisonInputs(const std::string& dir) {
  ComparisonOnDisk disk = ReadComparisonResults(dir);
  const std::string b = disk.folder_b.empty() ? "" : PipelineFolderOf(disk.folder_b);
  if (b.empty()) {
    throw InputError({(fs::path(dir) / ResultsManifest::kFileName).string(), 0, 0, "results_b"},
                     "the report of a comparison needs survey B's pipeline results (hullinspect-cli run), and this "
                     "comparison's manifest names " +
                         (disk.folder_b.empty() ? std::string("none") : "'" + disk.folder_b + "'"));
  }
  ReportInputs in = ReadReportInputs(b);
  auto run = std::make_shared<SurveyComparisonRun>();
  run->folder_a = disk.folder_a;
  run->folder_b = disk.folder_b;
  run->mesh = disk.mesh;
  if (in.mapping) run->objects_b = in.mapping->objects;
  run->comparison = std::move(disk.comparison);
  in.comparison = std::move(run);
  return in;
}

}  // namespace

const char* ReportSourceKindName(ReportSourceKind kind) {
  switch (kind) {
    case ReportSourceKind::kPipeline:
      return "pipeline";
    case ReportSourceKind::kComparison:
      return "comparison";
    case ReportSourceKind::kSonar:
      return "sonar";
  }
  return "?";
}

ReportSourceKind ClassifyReportSource(const std::string& results) {
  std::error_code ec;
  if (!fs::is_directory(results, ec)) {
    throw InputError({results, 0, 0, ""}, "no such results folder");
  }
  if (IsSonarResults(results)) return ReportSourceKind::kSonar;
  if (HasFile(results, "compare.json")) return ReportSourceKind::kComparison;
  if (!PipelineFolderOf(results).empty()) return ReportSourceKind::kPipeline;
  throw InputError({results, 0, 0, ""},
                   "holds no results a report can be written from: a pipeline's (summary.json of hullinspect-cli "
                   "run), a comparison's (compare.json) or a sonar run's");
}

void CheckFolderReportRequest(const FolderReportRequest& r) {
  if (r.out.path.empty()) throw OptionError("--out", "the report's folder is required");
  const ReportSourceKind kind = ClassifyReportSource(r.results);
  if (!r.earlier.empty() && kind != ReportSourceKind::kPipeline) {
    throw OptionError("--compare-with", std::string("goes with a pipeline's results, not a ") +
                                            ReportSourceKindName(kind) + "'s (a comparison already holds both)");
  }
  const std::string source = kind == ReportSourceKind::kPipeline ? PipelineFolderOf(r.results) : r.results;
  if (Within(r.out.path, source) && !Within(r.out.path, fs::path(source) / "report")) {
    // Replacing the results folder (or a folder inside it other than its
    // report/) would drop the results; a folder holding them, the same.
    throw OutputFolderRefused(r.out.path, "it is (or lies inside) the results folder " + source +
                                              "; write the report into a folder of its own, e.g. " +
                                              (fs::path(source) / "report").string());
  }
  if (Within(source, r.out.path)) {
    throw OutputFolderRefused(r.out.path, "it holds the results folder " + source + " the report is read from");
  }
  CheckResultsFolder(r.out);
}

ReportInputs ReadFolderReportInputs(const FolderReportRequest& r, Progress& progress) {
  progress.Update(0, "reading " + r.results);
  switch (ClassifyReportSource(r.results)) {
    case ReportSourceKind::kSonar: {
      ReportInputs in;
      in.sonar = std::make_shared<const SonarPipelineResult>(ReadSonarResults(r.results));
      in.results_path = fs::absolute(r.results).lexically_normal().string();
      return in;
    }
    case ReportSourceKind::kComparison:
      return ComparisonInputs(r.results);
    case ReportSourceKind::kPipeline:
      break;
  }
  ReportInputs in = ReadReportInputs(PipelineFolderOf(r.results));
  if (!r.earlier.empty()) {
    progress.Update(0.1, "comparing with the earlier survey " + r.earlier);
    in.comparison = std::make_shared<const SurveyComparisonRun>(
        RunSurveyComparison(r.earlier, in.results_path, in.mesh_path, 1.0, SurveyCompareOptions{}, progress));
  }
  return in;
}

ReportFiles WriteReportFolder(const ReportInputs& inputs, const OutputFolder& out, ResultsRun run, Progress& progress,
                              const ReportOptions& options) {
  ReportFiles files;
  WriteResultsFolder(out, run, [&](const std::string& tmp) {
    const QDir dir(QString::fromStdString(tmp));
    files = WriteReport(inputs, dir.filePath(QStringLiteral("report.html")), dir.filePath(QStringLiteral("report.pdf")),
                        options, dir.filePath(QStringLiteral("figures")), &progress);
  });
  // The paths where they now are.
  const QDir final_dir(QString::fromStdString(fs::absolute(out.path).lexically_normal().string()));
  files.html = final_dir.filePath(QStringLiteral("report.html"));
  files.pdf = final_dir.filePath(QStringLiteral("report.pdf"));
  for (QString& f : files.figures) {
    f = final_dir.filePath(QStringLiteral("figures/") + QFileInfo(f).fileName());
  }
  return files;
}

ReportFiles RunFolderReport(const FolderReportRequest& r, const std::string& command, Progress& progress) {
  CheckFolderReportRequest(r);
  const ReportInputs inputs = ReadFolderReportInputs(r, progress);
  ResultsRun run = NewResultsRun(command);
  run.AddResults("results", r.results);
  if (!r.earlier.empty()) run.AddResults("results_a", r.earlier);
  return WriteReportFolder(inputs, r.out, std::move(run), progress);
}

}  // namespace hull::report
