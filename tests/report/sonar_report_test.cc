// The sonar report (ui/report/sonar_report.h): every section present, the
// features listed, and an estimate whose normalised innovations are far
// outside their chi-square interval called INCONSISTENT, in the summary and
// its own section; a consistent one called consistent; no error figures or
// numbers without truth. Written as HTML and PDF like the hull report.
#include <gtest/gtest.h>

#include <QDir>
#include <QFile>
#include <filesystem>

#include "ui/report/report.h"
#include "ui/report/report_document.h"
#include "ui/report/sonar_report.h"

namespace hull::report {
namespace {

// A run of `steps` steps, each updating with 4 measurements (8 dof) whose
// NIS is `nis`, and two features, one placed and one waiting; no truth.
std::shared_ptr<SonarPipelineResult> SonarRun(int steps, double nis) {
  auto r = std::make_shared<SonarPipelineResult>();
  r->sequence = "/data/tank";
  for (int k = 0; k < steps; ++k) {
    SonarStepRecord s;
    s.estimate.step = k;
    s.estimate.pose << 0.1 * k, 0.02 * k, 0, 0, 0, 0;
    s.estimate.measurements = k == 1 ? 0 : 4;
    s.estimate.nis = k == 1 ? 0 : nis;
    s.estimate.nis_dof = k == 1 ? 0 : 8;
    s.dead_reckoning = s.estimate.pose;
    r->run.steps.push_back(s);
  }
  SonarFeatureEstimate placed;
  placed.id = 3;
  placed.position = {2.0, 0.5, -0.1};
  placed.covariance = Eigen::Matrix3d::Identity() * 1e-4;
  placed.observations = 5;
  SonarFeatureEstimate waiting = placed;
  waiting.id = 4;
  waiting.in_state = false;
  r->run.final_features = {placed, waiting};
  r->run.final_feature_errors = {NAN, NAN};
  return r;
}

std::string Text(const Section& s) {
  std::string t;
  for (const Block& b : s.blocks) {
    t += b.text + "\n";
    for (const auto& [k, v] : b.facts) t += k + ": " + v + "\n";
    for (const std::string& i : b.items) t += i + "\n";
  }
  return t;
}

ReportDocument Build(const std::shared_ptr<SonarPipelineResult>& run) {
  ReportInputs in;
  in.sonar = run;
  const std::vector<FigureRef> figures = PlanFigures(in, {});
  return BuildReportDocument(in, {}, figures, "generated");
}

TEST(SonarReport, ChiSquareIntervalOfTheConsistencyCheck) {
  const ConsistencyCheck c = CheckConsistency(30, 30);
  EXPECT_TRUE(c.known);
  EXPECT_TRUE(c.consistent);
  EXPECT_NEAR(c.low, 16.79, 0.01);  // chi-square(30): 2.5 % and 97.5 % quantiles
  EXPECT_NEAR(c.high, 46.98, 0.01);
  EXPECT_FALSE(CheckConsistency(46 * 30, 30).consistent);
  EXPECT_FALSE(CheckConsistency(NAN, 30).known);
  EXPECT_FALSE(CheckConsistency(1, 0).known);
}

TEST(SonarReport, AnInconsistentEstimateSaysSo) {
  const ReportDocument d = Build(SonarRun(10, 8 * 46.0));  // NIS 46 times its dof, as issue 26's images gave
  std::vector<std::string> ids;
  for (const Section& s : d.sections) ids.push_back(s.id);
  EXPECT_EQ(ids, SonarSectionIds());
  EXPECT_EQ(d.title, "Imaging-sonar report");
  const std::string summary = Text(*d.Find("summary"));
  EXPECT_NE(summary.find("INCONSISTENT"), std::string::npos) << summary;
  const std::string consistency = Text(*d.Find("consistency"));
  EXPECT_NE(consistency.find("INCONSISTENT"), std::string::npos) << consistency;
  EXPECT_NE(consistency.find("optimistic"), std::string::npos) << consistency;
  EXPECT_NE(consistency.find("6.8 times larger"), std::string::npos) << consistency;  // sqrt(46)
  // What could not be placed: the step without a measurement, the waiting feature.
  const std::string missing = Text(*d.Find("not-placed"));
  EXPECT_NE(missing.find("Steps without a measurement: 1 of 10 (1)"), std::string::npos) << missing;
  EXPECT_NE(missing.find("never placed (their elevation still unresolved at the end): 1."), std::string::npos);
  // Both features listed; no truth: no error column, no error figure, no numbers.
  const Section& features = *d.Find("features");
  ASSERT_EQ(features.blocks.size(), 2u);
  EXPECT_EQ(features.blocks[1].table.rows.size(), 2u);
  EXPECT_EQ(features.blocks[1].table.header.back(), "state");
  EXPECT_NE(Text(*d.Find("evaluation")).find("no truth"), std::string::npos);
  EXPECT_EQ(d.Find("trajectory")->blocks.size(), 1u);  // the plan view only
}

TEST(SonarReport, AConsistentEstimateIsCalledConsistent) {
  const ReportDocument d = Build(SonarRun(10, 8.0));
  const std::string consistency = Text(*d.Find("consistency"));
  EXPECT_EQ(consistency.find("INCONSISTENT"), std::string::npos) << consistency;
  EXPECT_NE(consistency.find(": consistent ("), std::string::npos) << consistency;
}

TEST(SonarReport, WritesHtmlAndPdf) {
  ReportInputs in;
  in.sonar = SonarRun(6, 8.0);
  const QString dir = QDir::temp().filePath(QStringLiteral("hi_sonar_report_test"));
  QDir(dir).removeRecursively();
  const ReportFiles files = WriteReport(in, dir + QStringLiteral("/report.html"), dir + QStringLiteral("/report.pdf"),
                                        {}, dir + QStringLiteral("/figures"));
  EXPECT_GE(files.pdf_pages, 2);
  ASSERT_EQ(files.figures.size(), 1);
  QFile html(files.html);
  ASSERT_TRUE(html.open(QIODevice::ReadOnly));
  const QByteArray bytes = html.readAll();
  EXPECT_TRUE(bytes.contains("Consistency of the estimate"));
  EXPECT_TRUE(bytes.contains("data:image/png;base64,"));
  QDir(dir).removeRecursively();
  // A run without steps is refused, as a hull report without its inputs.
  in.sonar = SonarRun(0, 0);
  EXPECT_THROW(WriteReport(in, dir + QStringLiteral("/r.html"), {}), std::invalid_argument);
}

}  // namespace
}  // namespace hull::report
