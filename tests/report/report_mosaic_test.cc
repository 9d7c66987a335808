// The report's Photomosaic section: a results folder with mosaic/mosaic.ply
// (here the demo's fused model coloured red on the bow half and blue on the
// stern half) gives a mosaic figure for every heatmap view, drawn in the
// mosaic's colours, in the "photomosaic" section; without a mosaic the
// section says how to make one; a mosaic.ply without colours is an error
// naming the file.
#include <gtest/gtest.h>

#include <QColor>
#include <QDir>
#include <QImage>
#include <algorithm>
#include <filesystem>

#include "base/error.h"
#include "geometry/mesh_io.h"
#include "report_fixture.h"
#include "ui/report/figures.h"
#include "ui/report/report_blocks.h"
#include "ui/report/report_document.h"
#include "ui/report/results_reader.h"

namespace hull::report {
namespace {

namespace fs = std::filesystem;
using test_data::Demo;

int CountKind(const std::vector<FigureRef>& figures, FigureKind kind) {
  int n = 0;
  for (const FigureRef& f : figures) n += f.kind == kind;
  return n;
}

std::string SectionText(const Section& s) {
  std::string t;
  for (const Block& b : s.blocks) {
    t += b.text + "\n";
    for (const auto& [k, v] : b.facts) t += k + ": " + v + "\n";
  }
  return t;
}

// A copy of the demo's results folder with RESULTS/mosaic/mosaic.ply: the
// fused model, red where x (in M) is below its median, blue elsewhere.
std::string ResultsWithMosaic(const std::string& name, bool coloured) {
  const fs::path dst = fs::path(Demo().directory) / name;
  fs::remove_all(dst);
  fs::copy(Demo().results, dst, fs::copy_options::recursive);
  TriangleMesh mosaic = Demo().full.mapping->model;
  mosaic.vertex_scalars.clear();
  if (coloured) {
    std::vector<double> xs;
    for (const auto& v : mosaic.vertices) xs.push_back(v.x());
    std::nth_element(xs.begin(), xs.begin() + xs.size() / 2, xs.end());
    const double median = xs[xs.size() / 2];
    std::vector<double> red, green, blue;
    for (const auto& v : mosaic.vertices) {
      const bool low = v.x() < median;
      red.push_back(low ? 220 : 30);
      green.push_back(40);
      blue.push_back(low ? 30 : 220);
    }
    mosaic.SetScalar("red", red);
    mosaic.SetScalar("green", green);
    mosaic.SetScalar("blue", blue);
  } else {
    mosaic.SetScalar("grey", std::vector<double>(mosaic.num_vertices(), 128));
  }
  fs::create_directories(dst / "mosaic");
  SaveMesh(mosaic, (dst / "mosaic" / "mosaic.ply").string());
  return dst.string();
}

TEST(ReportMosaic, FigurePlannedAndDrawnWhenTheResultsHaveAMosaic) {
  const ReportInputs in = ReadReportInputs(ResultsWithMosaic("results-with-mosaic", true));
  ASSERT_TRUE(in.mosaic);
  EXPECT_EQ(in.mosaic->num_faces(), Demo().full.mapping->model.num_faces());
  EXPECT_NE(in.mosaic_path.find("mosaic.ply"), std::string::npos);

  const std::vector<FigureRef> figures = PlanFigures(in, {});
  const int views = CountKind(figures, FigureKind::kHeatmap);
  ASSERT_GE(views, 1);
  EXPECT_EQ(CountKind(figures, FigureKind::kMosaic), views);

  const ReportDocument d = BuildReportDocument(in, {}, figures, "test");
  const Section* s = d.Find("photomosaic");
  ASSERT_NE(s, nullptr);
  int figure_blocks = 0;
  for (const Block& b : s->blocks) figure_blocks += b.kind == Block::Kind::kFigure;
  EXPECT_EQ(figure_blocks, views);
  const std::string text = SectionText(*s);
  EXPECT_NE(text.find("Triangles: " + Count(static_cast<long long>(in.mosaic->num_faces()))), std::string::npos)
      << text;

  // Drawn in the mosaic's colours: both halves of the hull show.
  for (const FigureRef& f : figures) {
    if (f.kind != FigureKind::kMosaic) continue;
    const QImage image = RenderFigure(*MakeFigure(f, in, {}), 800);
    ASSERT_FALSE(image.isNull()) << f.id;
    image.save(QDir(QString::fromStdString(Demo().directory)).filePath(QString::fromStdString(f.id) + ".png"));
    long long reddish = 0, bluish = 0;
    for (int y = 0; y < image.height(); ++y) {
      for (int x = 0; x < image.width(); ++x) {
        const QColor c = image.pixelColor(x, y);
        reddish += c.red() > 100 && c.red() > 2 * c.blue() && c.red() > 2 * c.green();
        bluish += c.blue() > 100 && c.blue() > 2 * c.red() && c.blue() > 2 * c.green();
      }
    }
    EXPECT_GT(reddish, 2000) << f.id;
    EXPECT_GT(bluish, 2000) << f.id;
  }
}

TEST(ReportMosaic, WithoutAMosaicTheSectionSaysHowToMakeOne) {
  const ReportInputs& in = Demo().full;
  ASSERT_FALSE(in.mosaic);
  const std::vector<FigureRef> figures = PlanFigures(in, {});
  EXPECT_EQ(CountKind(figures, FigureKind::kMosaic), 0);
  const ReportDocument d = BuildReportDocument(in, {}, figures, "test");
  EXPECT_NE(SectionText(*d.Find("photomosaic")).find("hullinspect-cli mosaic RESULTS"), std::string::npos);
}

TEST(ReportMosaic, AMosaicWithoutColoursIsAnError) {
  const std::string results = ResultsWithMosaic("results-with-grey-mosaic", false);
  try {
    ReadReportInputs(results);
    FAIL() << "no error for a mosaic.ply without red, green and blue";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mosaic.ply"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("red"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hull::report
