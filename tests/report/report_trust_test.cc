// The report's uncertainty and change sections on the demo survey (its
// adjustment gives landmark covariances, so the fused model has per-vertex
// sigmas): the sigma and significance heatmaps are planned and drawn, the
// significance count follows k, the objects table gives height ± sigma and
// the 95th percentile, and a comparison with a made-up earlier survey gives
// the "Change between surveys" section with its table and figure, in the
// document and in the PDF's text (pdftotext, when installed).
#include <gtest/gtest.h>

#include <QDir>
#include <QFile>
#include <QImage>
#include <QProcess>
#include <QStandardPaths>
#include <cmath>
#include <memory>

#include "mapping/vertex_significance.h"
#include "report_fixture.h"
#include "results/compare_files.h"
#include "ui/report/figures.h"
#include "ui/report/headless_job.h"
#include "ui/report/report.h"
#include "ui/report/report_blocks.h"
#include "ui/report/report_document.h"

namespace hull::report {
namespace {

using test_data::Demo;

std::string TextOf(const Section& s) {
  std::string t;
  for (const Block& b : s.blocks) {
    t += b.text + "\n";
    for (const auto& [k, v] : b.facts) t += k + ": " + v + "\n";
    for (const auto& row : b.table.rows) {
      for (const auto& cell : row) t += cell + " | ";
      t += "\n";
    }
  }
  return t;
}

int CountKind(const std::vector<FigureRef>& figures, FigureKind kind) {
  int n = 0;
  for (const FigureRef& f : figures) n += f.kind == kind;
  return n;
}

// The demo's mapping as survey B and a made-up earlier survey A: every
// vertex 4 cm lower within 0.3 m of B's first object (so it grew), and
// without B's last object (so it is new).
ReportInputs WithComparison() {
  ReportInputs in = Demo().full;
  const MappingResult& b = *in.mapping;
  EXPECT_GE(b.objects.size(), 2u);
  TriangleMesh model_a = b.model;
  std::vector<double> dev = *model_a.FindScalar("deviation");
  const Eigen::Vector3d grown = b.objects.front().centroid_m;
  for (std::size_t i = 0; i < dev.size(); ++i) {
    if ((model_a.vertices[i] - grown).norm() < 0.3) dev[i] -= 0.04;
  }
  // B's last object is new: not in A's heights either (compare looks an
  // object A's map lacks up in A's height field).
  const Eigen::Vector3d added = b.objects.back().centroid_m;
  for (std::size_t i = 0; i < dev.size(); ++i) {
    if ((model_a.vertices[i] - added).norm() < 0.35) dev[i] = 0;
  }
  model_a.SetScalar("deviation", dev);
  std::vector<DetectedObject> objects_a(b.objects.begin(), b.objects.end() - 1);
  objects_a.front().max_height -= 0.04;
  auto run = std::make_shared<SurveyComparisonRun>();
  run->folder_a = "earlier-survey/mapping";
  run->folder_b = "this-survey/mapping";
  run->comparison = CompareSurveys(*in.cad, model_a, objects_a, b.model, b.objects, SurveyCompareOptions{});
  in.comparison = run;
  return in;
}

TEST(ReportTrust, SigmaAndSignificanceFiguresAndCounts) {
  const ReportInputs& in = Demo().full;
  ASSERT_TRUE(HasVertexSigma(in.mapping->model)) << "the demo's adjustment gives covariances";
  const std::vector<FigureRef> figures = PlanFigures(in, {});
  const int views = CountKind(figures, FigureKind::kHeatmap);
  EXPECT_EQ(CountKind(figures, FigureKind::kSigmaHeatmap), views);
  EXPECT_EQ(CountKind(figures, FigureKind::kSignificanceHeatmap), views);
  EXPECT_EQ(CountKind(figures, FigureKind::kChangeHeatmap), 0);
  // The count in the text follows k.
  for (const double k : {1.96, 4.0}) {
    ReportOptions o;
    o.significance_k = k;
    const ReportDocument d = BuildReportDocument(in, o, PlanFigures(in, o), "test");
    const std::string text = TextOf(*d.Find("uncertainty"));
    const std::size_t n = CountSignificant(in.mapping->model, k);
    EXPECT_NE(text.find(Count(static_cast<long long>(n)) + " of "), std::string::npos) << text;
    EXPECT_NE(text.find("k = " + Num(k, 2)), std::string::npos) << text;
  }
  EXPECT_GT(CountSignificant(in.mapping->model, 1.96), CountSignificant(in.mapping->model, 4.0));
  // The figures are drawn: the sigma heatmap in its sequential colours, the
  // significance heatmap grey where nothing is significant.
  for (const FigureRef& f : figures) {
    if (f.kind != FigureKind::kSigmaHeatmap && f.kind != FigureKind::kSignificanceHeatmap) continue;
    const QImage image = RenderFigure(*MakeFigure(f, in, {}), 800);
    ASSERT_FALSE(image.isNull()) << f.id;
    image.save(QDir(QString::fromStdString(Demo().directory)).filePath(QString::fromStdString(f.id) + ".png"));
  }
  // Objects: max ± sigma and the 95th percentile.
  const ReportDocument d = BuildReportDocument(in, {}, figures, "test");
  const std::string objects = TextOf(*d.Find("objects"));
  EXPECT_NE(objects.find(" ± "), std::string::npos) << objects;
  const DetectedObject& o = in.mapping->objects.front();
  ASSERT_TRUE(std::isfinite(o.max_height_sigma));
  EXPECT_NE(objects.find(Num(o.max_height, 3) + " ± " + Num(o.max_height_sigma, 3)), std::string::npos) << objects;
  EXPECT_NE(objects.find(Num(o.p95_height, 3)), std::string::npos);
  // Without a comparison the change section says so.
  EXPECT_NE(TextOf(*d.Find("change")).find("No earlier survey"), std::string::npos);
}

TEST(ReportTrust, ChangeBetweenSurveysSection) {
  const ReportInputs in = WithComparison();
  const std::vector<FigureRef> figures = PlanFigures(in, {});
  EXPECT_EQ(CountKind(figures, FigureKind::kChangeHeatmap), CountKind(figures, FigureKind::kHeatmap));
  const ReportDocument d = BuildReportDocument(in, {}, figures, "test");
  const Section& s = *d.Find("change");
  const std::string text = TextOf(s);
  const auto& changes = in.comparison->comparison.objects;
  int tables = 0, figure_blocks = 0;
  for (const Block& b : s.blocks) {
    if (b.kind == Block::Kind::kTable) {
      ++tables;
      EXPECT_EQ(b.table.rows.size(), changes.size());
    }
    figure_blocks += b.kind == Block::Kind::kFigure;
  }
  EXPECT_EQ(tables, 1);
  EXPECT_EQ(figure_blocks, CountKind(figures, FigureKind::kChangeHeatmap));
  EXPECT_NE(text.find("grown | " + in.mapping->objects.front().id), std::string::npos) << text;
  EXPECT_NE(text.find("new | – | " + in.mapping->objects.back().id), std::string::npos) << text;
  EXPECT_NE(text.find("1 new, 1 grown, 0 shrunk, 0 removed"), std::string::npos) << text;

  const QString dir = QDir(QString::fromStdString(Demo().directory)).filePath(QStringLiteral("trust-report"));
  const ReportFiles files = WriteReport(in, dir + "/report.html", dir + "/report.pdf", {}, dir + "/figures");
  EXPECT_EQ(files.figures.size(), static_cast<int>(figures.size()));
  const QString html = [&] {
    QFile f(files.html);
    return f.open(QIODevice::ReadOnly) ? QString::fromUtf8(f.readAll()) : QString();
  }();
  EXPECT_TRUE(html.contains(QStringLiteral("<section id=\"change\">")));
  EXPECT_TRUE(html.contains(QStringLiteral("<section id=\"uncertainty\">")));
  const QString pdftotext = QStandardPaths::findExecutable(QStringLiteral("pdftotext"));
  if (pdftotext.isEmpty()) GTEST_SKIP() << "pdftotext (poppler-utils) not installed";
  QProcess p;
  p.start(pdftotext, {QStringLiteral("-layout"), files.pdf, QStringLiteral("-")});
  ASSERT_TRUE(p.waitForFinished(60000));
  ASSERT_EQ(p.exitCode(), 0);
  // The PDF sets "fi" and "fl" as ligatures, which pdftotext gives back as such.
  const QString pdf_text = QString::fromUtf8(p.readAllStandardOutput())
                               .replace(QChar(0xFB01), QStringLiteral("fi"))
                               .replace(QChar(0xFB02), QStringLiteral("fl"));
  for (const char* phrase : {"Change between surveys", "Uncertainty and significance", "Significant deviation",
                             "Uncertainty of the deviation", "Change in height since the earlier survey", "grown"}) {
    EXPECT_TRUE(pdf_text.contains(QString::fromLatin1(phrase))) << phrase;
  }
}

TEST(HeadlessCommand, CompareWithGoesWithReport) {
  const HeadlessCommand c =
      ParseHeadlessCommand({QStringLiteral("--report"), QStringLiteral("b"), QStringLiteral("--compare-with"),
                            QStringLiteral("a"), QStringLiteral("--out"), QStringLiteral("o")});
  EXPECT_TRUE(c.error.isEmpty()) << c.error.toStdString();
  EXPECT_EQ(c.earlier, QStringLiteral("a"));
  EXPECT_EQ(c.results, QStringLiteral("b"));
  EXPECT_FALSE(ParseHeadlessCommand({QStringLiteral("--demo"), QStringLiteral("--compare-with"), QStringLiteral("a")})
                   .error.isEmpty());
  EXPECT_FALSE(ParseHeadlessCommand({QStringLiteral("--report"), QStringLiteral("b"), QStringLiteral("--out"),
                                     QStringLiteral("o"), QStringLiteral("--compare-with")})
                   .error.isEmpty());
}

}  // namespace
}  // namespace hull::report
