// The inspection report: its document has every section, its figures are
// drawn (non-blank, the sizes asked for) without any display, the HTML embeds
// them, the PDF is a valid A4 document of several pages, and a results folder
// reads back into the same report. Runs on Qt's offscreen platform.
#include <gtest/gtest.h>

#include <QByteArray>
#include <QDir>
#include <QFile>
#include <QGuiApplication>
#include <QImage>
#include <QProcess>
#include <QRegularExpression>
#include <QSet>
#include <QStandardPaths>
#include <filesystem>
#include <stdexcept>

#include "report_fixture.h"
#include "ui/report/figure_geometry.h"
#include "ui/report/figures.h"
#include "ui/report/headless_job.h"
#include "ui/report/report.h"
#include "ui/report/report_document.h"
#include "ui/report/results_reader.h"

namespace hull::report {
namespace {

using test_data::Demo;
using test_data::DemoRun;

QString TestDir(const char* name) {
  return QDir(QString::fromStdString(Demo().directory)).filePath(QString::fromLatin1(name));
}

QByteArray ReadAll(const QString& path) {
  QFile f(path);
  return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

// Share of pixels that are not (nearly) white.
double InkShare(const QImage& image) {
  const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
  std::size_t ink = 0;
  for (int y = 0; y < rgb.height(); ++y) {
    const QRgb* row = reinterpret_cast<const QRgb*>(rgb.constScanLine(y));
    for (int x = 0; x < rgb.width(); ++x) ink += qGray(row[x]) < 240 ? 1 : 0;
  }
  return static_cast<double>(ink) / (static_cast<double>(rgb.width()) * rgb.height());
}

int DistinctColours(const QImage& image) {
  const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
  QSet<QRgb> colours;
  for (int y = 0; y < rgb.height(); y += 2) {
    const QRgb* row = reinterpret_cast<const QRgb*>(rgb.constScanLine(y));
    for (int x = 0; x < rgb.width(); x += 2) colours.insert(row[x] & 0xf0f0f0);
  }
  return colours.size();
}

// Pixels of a strong red (positive deviation in the heatmap's colour map).
int RedPixels(const QImage& image) {
  const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
  int n = 0;
  for (int y = 0; y < rgb.height(); ++y) {
    const QRgb* row = reinterpret_cast<const QRgb*>(rgb.constScanLine(y));
    for (int x = 0; x < rgb.width(); ++x) n += qRed(row[x]) > 150 && qGreen(row[x]) < 110 && qBlue(row[x]) < 110;
  }
  return n;
}

// Pages of a PDF as Qt writes it: one "/Type /Page" dictionary per page.
int CountPdfPages(const QByteArray& pdf) {
  const QString text = QLatin1String(pdf.constData(), pdf.size());  // binary: not up to the first NUL
  return static_cast<int>(text.count(QRegularExpression(QStringLiteral("/Type\\s*/Page\\b"))));
}

bool HasSection(const ReportDocument& d, const std::string& id) { return d.Find(id) != nullptr; }

std::string AllText(const Section& s) {
  std::string t;
  for (const Block& b : s.blocks) {
    t += b.text + "\n";
    for (const auto& item : b.items) t += item + "\n";
    for (const auto& [k, v] : b.facts) t += k + ": " + v + "\n";
  }
  return t;
}

const Block* FirstTable(const Section& s, std::size_t skip = 0) {
  for (const Block& b : s.blocks) {
    if (b.kind == Block::Kind::kTable && skip-- == 0) return &b;
  }
  return nullptr;
}

ReportDocument DocumentOf(const ReportInputs& in) { return BuildReportDocument(in, {}, PlanFigures(in, {}), "test"); }

TEST(ReportDocument, HasEverySectionInOrder) {
  const ReportDocument d = DocumentOf(Demo().full);
  ASSERT_EQ(d.sections.size(), SectionIds().size());
  for (std::size_t i = 0; i < d.sections.size(); ++i) {
    EXPECT_EQ(d.sections[i].id, SectionIds()[i]);
    EXPECT_FALSE(d.sections[i].title.empty());
    EXPECT_FALSE(d.sections[i].blocks.empty()) << d.sections[i].id;
  }
  EXPECT_EQ(d.subtitle, Demo().full.bundle->manifest.name);
}

TEST(ReportDocument, TablesFollowTheResults) {
  const DemoRun& run = Demo();
  const ReportDocument d = DocumentOf(run.full);
  // Summary: the survey's name, vehicle, keyframes, camera, mesh.
  const std::string summary = AllText(*d.Find("summary"));
  for (const char* key : {"Survey: ", "Vehicle: ", "Keyframes: ", "Duration: ", "Camera: stereo",
                          "Landmarks: ", "Prior mesh: ", "Mesh size: ", "Ground truth: present"}) {
    EXPECT_NE(summary.find(key), std::string::npos) << key;
  }
  // Method: every parameter the brief names.
  const Block* params = FirstTable(*d.Find("method"));
  ASSERT_NE(params, nullptr);
  std::string names;
  for (const auto& row : params->table.rows) names += row[0] + "|";
  for (const char* p : {"Surface model", "σ0", "σ1", "Decision boundary", "τ", "α", "ε", "Min points"}) {
    EXPECT_NE(names.find(p), std::string::npos) << p;
  }
  // Objects: one row per detected object.
  const Block* objects = FirstTable(*d.Find("objects"));
  ASSERT_FALSE(run.full.mapping->objects.empty());
  ASSERT_NE(objects, nullptr);
  EXPECT_EQ(objects->table.rows.size(), run.full.mapping->objects.size());
  // Zones: the IMO scale, the note on slime, one row per inspected zone, rated.
  const Section& zones = *d.Find("zones");
  EXPECT_NE(AllText(zones).find("invisible to geometry"), std::string::npos);
  const Block* scale = FirstTable(zones, 0);
  const Block* rated = FirstTable(zones, 1);
  ASSERT_NE(scale, nullptr);
  ASSERT_NE(rated, nullptr);
  EXPECT_EQ(scale->table.rows.size(), 5u);
  std::size_t inspected = 0;
  for (const ZoneAssessment& z : run.full.mapping->zones) inspected += z.rating != FoulingRating::kUninspected;
  EXPECT_GT(inspected, 0u);
  EXPECT_EQ(rated->table.rows.size(), inspected);
  EXPECT_EQ(rated->table.header.back(), "Rating");
  EXPECT_EQ(rated->table.tone.size(), inspected);
  // Solver: a row per model; evaluation: a column per model.
  EXPECT_EQ(FirstTable(*d.Find("solver"))->table.rows.size(), 3u);
  EXPECT_EQ(FirstTable(*d.Find("evaluation"))->table.header.size(), 4u);
  // Not inspected: zones, skipped landmarks, DVL beams without returns.
  const std::string missing = AllText(*d.Find("not-inspected"));
  for (const char* key : {"Uninspected zones", "Landmarks left out", "DVL beams without a return"}) {
    EXPECT_NE(missing.find(key), std::string::npos) << key;
  }
}

TEST(ReportDocument, SaysWhatIsMissing) {
  const DemoRun& run = Demo();
  const ReportDocument no_map = DocumentOf(run.no_mapping);
  EXPECT_NE(AllText(*no_map.Find("objects")).find("Mapping has not run"), std::string::npos);
  EXPECT_NE(AllText(*no_map.Find("zones")).find("Mapping has not run"), std::string::npos);
  EXPECT_NE(AllText(*no_map.Find("not-inspected")).find("Mapping has not run"), std::string::npos);
  const ReportDocument no_truth = DocumentOf(run.no_truth);
  EXPECT_NE(AllText(*no_truth.Find("evaluation")).find("no ground truth"), std::string::npos);
  EXPECT_EQ(FirstTable(*no_truth.Find("evaluation")), nullptr);
  const ReportDocument one = DocumentOf(run.one_model);
  EXPECT_NE(AllText(*one.Find("cross-section")).find("one column"), std::string::npos);
  for (const ReportDocument* d : {&no_map, &no_truth, &one}) {
    for (const std::string& id : SectionIds()) EXPECT_TRUE(HasSection(*d, id)) << id;
  }
}

TEST(ReportFigures, PlannedForWhatRan) {
  const DemoRun& run = Demo();
  std::vector<std::string> ids;
  for (const FigureRef& f : PlanFigures(run.full, {})) ids.push_back(f.id);
  for (const char* id : {"heatmap-bottom", "cross-section", "solver-convergence", "dvl-residuals", "model-timing"}) {
    EXPECT_NE(std::find(ids.begin(), ids.end(), id), ids.end()) << id;
  }
  for (const FigureRef& f : PlanFigures(run.one_model, {})) EXPECT_NE(f.kind, FigureKind::kModelTiming);
  bool heatmap = false;
  for (const FigureRef& f : PlanFigures(run.no_mapping, {})) heatmap = heatmap || f.kind == FigureKind::kHeatmap;
  EXPECT_TRUE(heatmap) << "without mapping the heatmap shows the landmarks";
}

TEST(ReportFigures, NonBlankAtTheSizeAsked) {
  const DemoRun& run = Demo();
  for (const ReportInputs* in : {&run.full, &run.no_mapping, &run.one_model}) {
    for (const FigureRef& ref : PlanFigures(*in, {})) {
      const auto figure = MakeFigure(ref, *in, {});
      ASSERT_GT(figure->Height(), 100) << ref.id;
      for (int width : {900, 1600}) {
        const QImage image = RenderFigure(*figure, width);
        EXPECT_EQ(image.width(), width) << ref.id;
        EXPECT_EQ(image.height(), FigureHeightPx(*figure, width)) << ref.id;
        EXPECT_NEAR(static_cast<double>(image.height()) / width, figure->Height() / kFigureWidth, 2.0 / width);
        EXPECT_GT(InkShare(image), 0.03) << ref.id << " is nearly blank";
        EXPECT_GT(DistinctColours(image), 12) << ref.id;
      }
    }
  }
}

TEST(ReportFigures, HeatmapShowsTheObjectsInRed) {
  const DemoRun& run = Demo();
  FigureRef ref;
  for (const FigureRef& f : PlanFigures(run.full, {})) {
    if (f.id == "heatmap-bottom") ref = f;
  }
  ASSERT_EQ(ref.id, "heatmap-bottom");
  const QImage image = RenderFigure(*MakeFigure(ref, run.full, {}), 1600);
  EXPECT_GT(RedPixels(image), 200);
}

// A row of touching lumps along the keel, 20 units apart, labels 60 x 18:
// every label inside the panel, none over another label or over an object.
TEST(ReportFigures, LabelsOfARowOfObjectsDoNotOverlap) {
  const Eigen::AlignedBox2d bounds(Eigen::Vector2d(0, 0), Eigen::Vector2d(800, 400));
  std::vector<Eigen::Vector2d> anchors, sizes;
  for (int i = 0; i < 10; ++i) {
    anchors.emplace_back(200 + 20 * i, 200);
    sizes.emplace_back(60, 18);
  }
  const std::vector<Eigen::AlignedBox2d> boxes = PlaceLabels(bounds, anchors, sizes);
  ASSERT_EQ(boxes.size(), anchors.size());
  // The first takes the preferred spot: right of and above its object.
  EXPECT_DOUBLE_EQ(boxes[0].min().x(), 210);
  EXPECT_DOUBLE_EQ(boxes[0].min().y(), 178);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    EXPECT_TRUE(bounds.contains(boxes[i])) << i;
    EXPECT_DOUBLE_EQ(boxes[i].sizes().x(), 60);
    for (std::size_t j = 0; j < i; ++j) EXPECT_TRUE(boxes[i].intersection(boxes[j]).isEmpty()) << i << " " << j;
    for (const Eigen::Vector2d& a : anchors) EXPECT_FALSE(boxes[i].contains(a)) << i;
  }
  // Crowded beyond eight steps: still one box each, overlapping least.
  const Eigen::AlignedBox2d small(Eigen::Vector2d(0, 0), Eigen::Vector2d(120, 60));
  EXPECT_EQ(PlaceLabels(small, anchors, sizes).size(), anchors.size());
}

TEST(ReportFigures, CrossSectionHasEveryModelAndTheObject) {
  const DemoRun& run = Demo();
  const HullFrame hull = ReportHullFrame(run.full);
  const CrossSection cs = BuildCrossSection(run.full, hull, {});
  ASSERT_EQ(cs.models.size(), 3u);
  EXPECT_EQ(cs.models[0].model, SurfaceModel::kNaive);
  EXPECT_EQ(cs.models[1].model, SurfaceModel::kAllOnSurface);
  EXPECT_EQ(cs.models[2].model, SurfaceModel::kMaxMixture);
  EXPECT_FALSE(cs.cad.empty());
  EXPECT_FALSE(cs.focus.empty()) << "the slab goes through a detected object";
  for (const SectionModel& m : cs.models) {
    EXPECT_GT(m.features.size(), 10u);
    EXPECT_GT(m.dvl.size(), 0u);
  }
  EXPECT_FALSE(cs.models[2].fused.empty());
  int off = 0;
  for (const SectionFeature& f : cs.models[2].features) off += f.off_hull;
  EXPECT_GT(off, 0) << "the max-mixture keeps the object's features off the hull";
  EXPECT_EQ(BuildCrossSection(run.one_model, hull, {}).models.size(), 1u);
  // A slab placed by hand.
  ReportOptions o;
  o.slab_from_bow = cs.from_bow + 1.0;
  o.slab_width = 0.5;
  const CrossSection moved = BuildCrossSection(run.full, hull, o);
  EXPECT_DOUBLE_EQ(moved.from_bow, cs.from_bow + 1.0);
  EXPECT_DOUBLE_EQ(moved.width, 0.5);
}

TEST(ReportFiles, HtmlAndPdfWithEverything) {
  const DemoRun& run = Demo();
  const QString dir = TestDir("report");
  ReportOptions options;
  options.figure_width_px = 1400;
  const ReportFiles files = WriteReport(run.full, dir + "/report.html", dir + "/report.pdf", options, dir + "/figures");
  const std::vector<FigureRef> refs = PlanFigures(run.full, options);
  ASSERT_EQ(files.figures.size(), static_cast<int>(refs.size()));
  for (const QString& png : files.figures) {
    const QImage image(png);
    ASSERT_FALSE(image.isNull()) << png.toStdString();
    EXPECT_EQ(image.width(), 1400);
  }
  // HTML: every section, every figure embedded as a PNG data URI.
  const QString html = QString::fromUtf8(ReadAll(files.html));
  for (const std::string& id : SectionIds()) {
    EXPECT_TRUE(html.contains(QStringLiteral("<section id=\"%1\">").arg(QString::fromStdString(id)))) << id;
  }
  const QRegularExpression uri(QStringLiteral("src=\"data:image/png;base64,([A-Za-z0-9+/=]+)\""));
  int embedded = 0;
  for (auto it = uri.globalMatch(html); it.hasNext(); ++embedded) {
    const QImage image = QImage::fromData(QByteArray::fromBase64(it.next().captured(1).toLatin1()), "PNG");
    EXPECT_EQ(image.width(), 1400);
  }
  EXPECT_EQ(embedded, static_cast<int>(refs.size()));
  EXPECT_FALSE(html.contains(QStringLiteral("src=\"figures/"))) << "self-contained";
  EXPECT_TRUE(html.contains(QStringLiteral("invisible to geometry")));
  // PDF: valid, A4, several pages.
  const QByteArray pdf = ReadAll(files.pdf);
  ASSERT_GT(pdf.size(), 20000);
  EXPECT_TRUE(pdf.startsWith("%PDF-1."));
  EXPECT_TRUE(pdf.trimmed().endsWith("%%EOF"));
  EXPECT_GE(files.pdf_pages, 8);
  EXPECT_EQ(CountPdfPages(pdf), files.pdf_pages);
  EXPECT_TRUE(pdf.contains("/MediaBox [0 0 595"));  // A4: 595 x 842 pt
  EXPECT_FALSE(QFile::exists(files.pdf + ".part"));
  // An independent reader, when installed (poppler-utils).
  const QString pdfinfo = QStandardPaths::findExecutable(QStringLiteral("pdfinfo"));
  if (!pdfinfo.isEmpty()) {
    QProcess p;
    p.start(pdfinfo, {files.pdf});
    ASSERT_TRUE(p.waitForFinished(60000));
    EXPECT_EQ(p.exitCode(), 0);
    const QString info = QString::fromLocal8Bit(p.readAllStandardOutput());
    EXPECT_TRUE(info.contains(QRegularExpression(QStringLiteral("Pages:\\s+%1\\n").arg(files.pdf_pages))))
        << info.toStdString();
    EXPECT_TRUE(info.contains(QStringLiteral("(A4)"))) << info.toStdString();
  }
}

TEST(ReportFiles, VariantsWriteToo) {
  const DemoRun& run = Demo();
  int k = 0;
  for (const ReportInputs* in : {&run.no_mapping, &run.one_model, &run.no_truth}) {
    const QString dir = TestDir("variants") + QString::number(k++);
    const ReportFiles f = WriteReport(*in, dir + "/report.html", dir + "/report.pdf", {}, dir + "/figures");
    EXPECT_GE(f.pdf_pages, 5);
    EXPECT_TRUE(QFile::exists(f.html));
    EXPECT_EQ(f.figures.size(), static_cast<int>(PlanFigures(*in, {}).size()));
  }
  // Either file may be skipped.
  const QString dir = TestDir("html-only");
  const ReportFiles html_only = WriteReport(run.one_model, dir + "/r.html", {});
  EXPECT_TRUE(html_only.pdf.isEmpty());
  EXPECT_TRUE(html_only.figures.isEmpty());
  EXPECT_FALSE(QFile::exists(dir + "/r.pdf"));
}

TEST(ReportFiles, ReadBackFromAResultsFolder) {
  const DemoRun& run = Demo();
  const ReportInputs in = ReadReportInputs(run.results);
  ASSERT_TRUE(in.mapping);
  EXPECT_EQ(in.pipeline->baselines.size(), 2u);
  EXPECT_TRUE(in.pipeline->evaluation.has_value());
  EXPECT_EQ(in.pipeline->adjustment.landmarks.size(), run.full.pipeline->adjustment.landmarks.size());
  EXPECT_EQ(in.mapping->objects.size(), run.full.mapping->objects.size());
  EXPECT_EQ(in.mapping->zones.size(), run.full.mapping->zones.size());
  EXPECT_EQ(in.mapping->model.num_faces(), run.full.mapping->model.num_faces());
  ASSERT_NE(in.mapping->model.FindScalar("deviation"), nullptr);
  EXPECT_NEAR(in.mapping->hull.length(), run.full.mapping->hull.length(), 1e-9);
  const ReportDocument a = DocumentOf(run.full), b = DocumentOf(in);
  EXPECT_EQ(FirstTable(*a.Find("objects"))->table.rows, FirstTable(*b.Find("objects"))->table.rows);
  EXPECT_EQ(FirstTable(*a.Find("zones"), 1)->table.rows, FirstTable(*b.Find("zones"), 1)->table.rows);
  const QString dir = TestDir("read-back");
  EXPECT_GE(WriteReport(in, dir + "/report.html", dir + "/report.pdf").pdf_pages, 8);
  EXPECT_THROW(ReadReportInputs(run.directory + "/no-such-folder"), InputError);
}

TEST(ReportFiles, UnwritablePathsThrow) {
  const DemoRun& run = Demo();
  const QString blocker = TestDir("a-file");
  QFile f(blocker);
  ASSERT_TRUE(f.open(QIODevice::WriteOnly));
  f.close();
  EXPECT_THROW(WriteReport(run.one_model, blocker + "/report.html", {}), std::runtime_error);
  EXPECT_THROW(WriteReport(run.one_model, {}, blocker + "/report.pdf"), std::runtime_error);
}

TEST(ReportInputs, MissingPiecesAreRefused) {
  ReportInputs in = Demo().full;
  in.pipeline.reset();
  EXPECT_THROW(CheckInputs(in), std::invalid_argument);
  EXPECT_THROW(WriteReport(in, TestDir("refused") + "/r.html", {}), std::invalid_argument);
  in = Demo().full;
  in.cad.reset();
  EXPECT_THROW(CheckInputs(in), std::invalid_argument);
  in = Demo().full;
  in.bundle.reset();
  EXPECT_THROW(CheckInputs(in), std::invalid_argument);
}

TEST(HeadlessCommand, Parses) {
  using M = HeadlessCommand::Mode;
  HeadlessCommand c = ParseHeadlessCommand({QStringLiteral("--demo")});
  EXPECT_EQ(c.mode, M::kDemo);
  EXPECT_EQ(c.out, QStringLiteral("demo-output"));
  EXPECT_TRUE(c.error.isEmpty());
  c = ParseHeadlessCommand({QStringLiteral("--demo"), QStringLiteral("--out"), QStringLiteral("x")});
  EXPECT_EQ(c.out, QStringLiteral("x"));
  c = ParseHeadlessCommand(
      {QStringLiteral("--report"), QStringLiteral("r"), QStringLiteral("--out"), QStringLiteral("o")});
  EXPECT_EQ(c.mode, M::kReport);
  EXPECT_EQ(c.results, QStringLiteral("r"));
  EXPECT_TRUE(c.error.isEmpty());
  EXPECT_FALSE(ParseHeadlessCommand({QStringLiteral("--report"), QStringLiteral("r")}).error.isEmpty());
  EXPECT_FALSE(ParseHeadlessCommand({QStringLiteral("--out")}).error.isEmpty());
  EXPECT_FALSE(ParseHeadlessCommand({}).error.isEmpty());
  EXPECT_FALSE(ParseHeadlessCommand({QStringLiteral("--demo"), QStringLiteral("hull.ply")}).error.isEmpty());
  EXPECT_FALSE(ParseHeadlessCommand({QStringLiteral("--demo"), QStringLiteral("--report"), QStringLiteral("r")})
                   .error.isEmpty());
  EXPECT_TRUE(IsBatchCommand({QStringLiteral("--report"), QStringLiteral("r")}));
  EXPECT_TRUE(IsBatchCommand({QStringLiteral("--demo"), QStringLiteral("--out"), QStringLiteral("d")}));
  EXPECT_FALSE(IsBatchCommand({QStringLiteral("--demo")}));
}

}  // namespace
}  // namespace hull::report

int main(int argc, char** argv) {
  qputenv("QT_QPA_PLATFORM", "offscreen");  // no display needed, ever
  QGuiApplication app(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
