// The uncertainty and change views of issue 12: the sigma and significance
// heatmaps in the 3-D scene (toggled in the layers, each rendering its own
// image with its legend), the significance factor k from the parameter panel
// (with undo) changing the mask without a re-run, the objects table's
// height ± sigma, and "Compare with…" on two synthetic results folders (the
// height-change layer, its legend and the matched-objects table).
#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QPushButton>
#include <QTableView>
#include <QUndoStack>
#include <cmath>
#include <filesystem>
#include <optional>

#include "base/progress.h"
#include "geometry/mesh_io.h"
#include "gui_test_support.h"
#include "inspection_window.h"
#include "mapping/mapping_result.h"
#include "mapping/vertex_significance.h"
#include "synthetic_results.h"
#include "synthetic_survey.h"
#include "ui/controllers/survey_compare_controller.h"
#include "ui/models/objects_table_model.h"
#include "ui/panels/layers_panel.h"
#include "ui/panels/objects_panel.h"
#include "ui/panels/survey_compare_panel.h"
#include "ui/views/scene_view.h"

using namespace hull::ui;
using namespace hull::ui::testing;

namespace {

// Share of pixels whose channels differ by more than 40.
double DifferentPixels(const QImage& a, const QImage& b) {
  if (a.size() != b.size()) return 1.0;
  const QImage x = a.convertToFormat(QImage::Format_RGB32), y = b.convertToFormat(QImage::Format_RGB32);
  long long n = 0;
  for (int r = 0; r < x.height(); ++r) {
    const QRgb* p = reinterpret_cast<const QRgb*>(x.constScanLine(r));
    const QRgb* q = reinterpret_cast<const QRgb*>(y.constScanLine(r));
    for (int c = 0; c < x.width(); ++c) {
      n += std::abs(qRed(p[c]) - qRed(q[c])) > 40 || std::abs(qGreen(p[c]) - qGreen(q[c])) > 40 ||
           std::abs(qBlue(p[c]) - qBlue(q[c])) > 40;
    }
  }
  return static_cast<double>(n) / (static_cast<double>(x.width()) * x.height());
}

// Brute force: vertices with |deviation| > k sigma.
std::size_t Significant(const hull::TriangleMesh& m, double k) {
  const auto& d = *m.FindScalar("deviation");
  const auto& s = *m.FindScalar("sigma");
  std::size_t n = 0;
  for (std::size_t i = 0; i < d.size(); ++i) n += std::isfinite(s[i]) && std::abs(d[i]) > k * s[i];
  return n;
}

SceneOptions OnlyLayer(SceneLayer shown) {
  SceneOptions o;
  for (SceneLayer layer : AllSceneLayers()) o.visible[layer] = false;
  o.visible[shown] = true;
  o.visible[SceneLayer::kDetectedObjects] = true;
  o.auto_range = false;
  o.range_min = -0.15;
  o.range_max = 0.15;
  return o;
}

// The synthetic mapping written as results folders: A as mapped, B with the
// first object grown by 5 cm, the second removed and a new lump elsewhere.
struct ComparePair {
  QString a, b;
  std::string first_id, second_id;
};

ComparePair WriteComparePair() {
  namespace fs = std::filesystem;
  const auto& survey = MakeSyntheticSurvey();
  const fs::path root = fs::path(OutputDir().toStdString()) / "compare-pair";
  fs::create_directories(root);
  const std::string mesh = (root / "hull.ply").string();
  hull::SaveMesh(*survey.mesh, mesh);
  hull::MappingResult a = *SyntheticMapping()->result;
  a.inputs = {{"mesh", mesh}};
  hull::MappingResult b = a;
  std::vector<double> dev = *b.model.FindScalar("deviation");
  const Eigen::Vector3d grown = b.objects.at(0).centroid_m;
  for (std::size_t i = 0; i < dev.size(); ++i) {
    if ((b.model.vertices[i] - grown).norm() < 0.25) dev[i] += 0.05;
  }
  b.objects[0].max_height += 0.05;
  // The removed object: gone from B's height field too (compare looks an
  // object B's map lacks up in B's heights).
  const Eigen::Vector3d removed = b.objects.at(1).centroid_m;
  for (std::size_t i = 0; i < dev.size(); ++i) {
    if ((b.model.vertices[i] - removed).norm() < 0.35) dev[i] = 0;
  }
  ComparePair pair;
  pair.first_id = b.objects[0].id;
  pair.second_id = b.objects.at(1).id;
  // The new lump: 8 cm at the vertex farthest from every object.
  std::size_t far = 0;
  double best = -1;
  for (std::size_t i = 0; i < dev.size(); ++i) {
    double d = 1e9;
    for (const auto& o : a.objects) d = std::min(d, (b.model.vertices[i] - o.centroid_m).norm());
    if (d > best && d < 1.0) {
      best = d;
      far = i;
    }
  }
  for (std::size_t i = 0; i < dev.size(); ++i) {
    const double r = (b.model.vertices[i] - b.model.vertices[far]).norm();
    if (r < 0.1) dev[i] = std::max(dev[i], 0.08 * (1 - r / 0.1));
  }
  b.model.SetScalar("deviation", dev);
  hull::DetectedObject added;
  added.id = "obj-new";
  added.centroid_m = b.model.vertices[far];
  added.max_height = 0.08;
  b.objects.erase(b.objects.begin() + 1);
  b.objects.push_back(added);
  pair.a = QString::fromStdString((root / "a").string());
  pair.b = QString::fromStdString((root / "b").string());
  hull::WriteMappingResult(a, pair.a.toStdString());
  hull::WriteMappingResult(b, pair.b.toStdString());
  return pair;
}

}  // namespace

class TrustViewsTest : public QObject {
  Q_OBJECT

 private slots:
  void sigmaAndSignificanceLayers() {
    const auto& survey = MakeSyntheticSurvey();
    const auto mapping = SyntheticMapping();
    const hull::TriangleMesh& model = mapping->result->model;
    QVERIFY(hull::HasVertexSigma(model));
    SceneView scene;
    scene.setFixedSize(640, 480);
    scene.SetMesh(survey.mesh);
    scene.SetSurvey(survey.bundle, std::make_shared<SurveyOverlays>(ComputeSurveyOverlays(*survey.bundle)));
    scene.SetModelPose(PlacementPose(survey.bundle.get(), ModelPlacement::kTruth));
    scene.SetMapping(mapping);
    scene.SetOptions(OnlyLayer(SceneLayer::kHeatmap));
    scene.show();
    QVERIFY(QTest::qWaitForWindowExposed(&scene));
    LookAtTheCylinder(scene);
    QVERIFY(scene.Stats(SceneLayer::kSigmaHeatmap).present && scene.Stats(SceneLayer::kSignificance).present);
    QVERIFY(!scene.Stats(SceneLayer::kSigmaHeatmap).visible);
    const QImage deviation = scene.Grab();
    QVERIFY(scene.LegendVisible() && !scene.SigmaLegendVisible());

    scene.SetOptions(OnlyLayer(SceneLayer::kSigmaHeatmap));
    QVERIFY(scene.Stats(SceneLayer::kSigmaHeatmap).visible && !scene.Stats(SceneLayer::kHeatmap).visible);
    QVERIFY(scene.SigmaLegendVisible() && !scene.LegendVisible());
    // The sigma legend in mm up to the largest sigma (2 to 5 mm made up).
    QCOMPARE(scene.SigmaLegendRange().first, 0.0);
    QVERIFY(std::abs(scene.SigmaLegendRange().second - 1000.0 * hull::MaxVertexSigma(model)) < 1e-9);
    QVERIFY(scene.SigmaLegendRange().second > 2.0 && scene.SigmaLegendRange().second <= 5.0 + 1e-9);
    const QImage sigma = scene.Grab();
    Check(sigma, QStringLiteral("scene_sigma"));

    scene.SetOptions(OnlyLayer(SceneLayer::kSignificance));
    QVERIFY(scene.LegendVisible() && !scene.SigmaLegendVisible());
    const QImage significance = scene.Grab();
    Check(significance, QStringLiteral("scene_significance"));
    QVERIFY2(DifferentPixels(deviation, sigma) > 0.05, "the sigma layer looks like the deviation heatmap");
    QVERIFY2(DifferentPixels(sigma, significance) > 0.05, "the significance layer looks like the sigma layer");
    QVERIFY2(DifferentPixels(deviation, significance) > 0.005,
             "the significance layer looks like the deviation heatmap");

    // k: the mask follows, counted as by brute force.
    QCOMPARE(scene.SignificantVertices(), Significant(model, 1.96));
    QVERIFY(Significant(model, 1.96) > 0);
    scene.SetSignificanceK(20.0);
    QCOMPARE(scene.SignificantVertices(), Significant(model, 20.0));
    QVERIFY(Significant(model, 20.0) < Significant(model, 1.96));
    const QImage strict = scene.Grab();
    QVERIFY2(DifferentPixels(significance, strict) > 0.0, "a larger k greys out no more of the model");
  }

  // Measure anywhere (issue 25): a click on the remeshed model reads the
  // deviation, sigma and significance of the vertex under it as model.ply
  // holds them, and the object it belongs to; a click on the CAD says where
  // on the hull it is.
  void pickTheRemeshedSurfaceAndTheCad() {
    namespace fs = std::filesystem;
    const auto& survey = MakeSyntheticSurvey();
    const auto mapping = SyntheticMapping();
    const fs::path folder = fs::path(OutputDir().toStdString()) / "picked-mapping";
    hull::WriteMappingResult(*mapping->result, folder.string());
    const hull::TriangleMesh saved = hull::LoadMesh((folder / "model.ply").string());
    const hull::TriangleMesh& model = mapping->result->model;
    QCOMPARE(saved.num_vertices(), model.num_vertices());
    SceneView scene;
    scene.setFixedSize(640, 480);
    scene.SetMesh(survey.mesh);
    scene.SetSurvey(survey.bundle, std::make_shared<SurveyOverlays>(ComputeSurveyOverlays(*survey.bundle)));
    scene.SetModelPose(PlacementPose(survey.bundle.get(), ModelPlacement::kTruth));
    scene.SetMapping(mapping);
    SceneOptions only_model = OnlyLayer(SceneLayer::kHeatmap);
    only_model.visible[SceneLayer::kDetectedObjects] = false;  // outlines are picked before surfaces
    scene.SetOptions(only_model);
    scene.show();
    QVERIFY(QTest::qWaitForWindowExposed(&scene));
    LookAtTheCylinder(scene);
    scene.Grab();

    // The highest vertex of an object in view.
    const std::vector<double>& deviation = *saved.FindScalar("deviation");
    const hull::DetectedObject* object = nullptr;
    int peak = -1;
    std::optional<QPoint> at;
    for (const hull::DetectedObject& o : mapping->result->objects) {
      if (o.vertices.empty()) continue;
      int top = o.vertices.front();
      for (const int v : o.vertices) {
        if (deviation[static_cast<std::size_t>(v)] > deviation[static_cast<std::size_t>(top)]) top = v;
      }
      const auto p = scene.WidgetPosition(mapping->x_gM() * model.vertices[static_cast<std::size_t>(top)]);
      if (p && QRect(20, 20, 600, 440).contains(*p)) {
        object = &o;
        peak = top;
        at = p;
        break;
      }
    }
    QVERIFY2(object, "no detected object in view");
    const PickInfo info = scene.PickAt(*at);
    QCOMPARE(info.kind, PickKind::kSurface);
    QVERIFY2(info.title.startsWith(QStringLiteral("Remeshed model")), qPrintable(info.title));
    const int picked = info.id.section(QLatin1Char(' '), -1).toInt();
    // The click lands within a pixel of the peak: the peak or a neighbour.
    QVERIFY((model.vertices[static_cast<std::size_t>(picked)] - model.vertices[static_cast<std::size_t>(peak)]).norm() <
            0.05);
    auto row = [&](const PickInfo& i, const QString& label) {
      for (const auto& r : i.rows) {
        if (r.first == label) return r.second;
      }
      return QString();
    };
    const double h = deviation[static_cast<std::size_t>(picked)];
    QCOMPARE(row(info, QStringLiteral("Deviation")), QString::asprintf("%+.1f mm", h * 1000.0));
    const double sigma = (*saved.FindScalar("sigma"))[static_cast<std::size_t>(picked)];
    QCOMPARE(row(info, QStringLiteral("σ")), QString::asprintf("%.1f mm", sigma * 1000.0));
    QVERIFY(row(info, QStringLiteral("Significant")).startsWith(std::abs(h) > 1.96 * sigma ? "yes" : "no"));
    QCOMPARE(row(info, QStringLiteral("Object")), QString::fromStdString(object->id) + QStringLiteral(" (on it)"));
    QVERIFY(row(info, QStringLiteral("Where")).contains(QStringLiteral("m from the bow, station")));
    QVERIFY(info.position.has_value());

    // The CAD: on it by definition, and where on the hull.
    SceneOptions only_cad = only_model;
    only_cad.visible[SceneLayer::kHeatmap] = false;
    only_cad.visible[SceneLayer::kHull] = true;
    scene.SetOptions(only_cad);
    scene.Grab();
    const PickInfo cad = scene.PickAt(*at);
    QCOMPARE(cad.kind, PickKind::kSurface);
    QVERIFY2(cad.title.startsWith(QStringLiteral("CAD surface")), qPrintable(cad.title));
    QCOMPARE(row(cad, QStringLiteral("Deviation")), QStringLiteral("0 mm (the CAD itself)"));
    QVERIFY(row(cad, QStringLiteral("Where")).contains(QStringLiteral("m from the bow")));

    // No surface shown: nothing picked there.
    SceneOptions none = only_cad;
    none.visible[SceneLayer::kHull] = false;
    scene.SetOptions(none);
    scene.Grab();
    QCOMPARE(scene.PickAt(*at).kind, PickKind::kNone);
  }

  void kFromTheParameterPanelWithUndo() {
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    // The synthetic objects stand more than 10 sigma (the panel's largest k)
    // off the hull: sigmas ten times larger put them within reach.
    auto result = std::make_shared<hull::MappingResult>(*SyntheticMapping()->result);
    std::vector<double> sigma = *result->model.FindScalar("sigma");
    for (double& v : sigma) v *= 10.0;
    result->model.SetScalar("sigma", sigma);
    auto run = std::make_shared<MappingRun>(*SyntheticMapping());
    run->result = result;
    const std::shared_ptr<const MappingRun> mapping = run;
    const hull::TriangleMesh& model = mapping->result->model;
    win.w.session()->SetMapping(mapping);
    SceneView* scene = win.w.sceneView();
    QVERIFY(win.w.layersPanel()->layerCheckBox(SceneLayer::kSignificance)->isEnabled());
    win.w.layersPanel()->layerCheckBox(SceneLayer::kSignificance)->setChecked(true);
    QVERIFY(scene->Stats(SceneLayer::kSignificance).visible);
    QCOMPARE(scene->SignificantVertices(), Significant(model, 1.96));
    const int undo_before = win.w.parameterPanel()->undoStack()->count();
    QDoubleSpinBox* k = win.Real("significance_k");
    QVERIFY(k);
    k->setValue(5.0);
    QCOMPARE(scene->SignificantVertices(), Significant(model, 5.0));
    QVERIFY(Significant(model, 5.0) < Significant(model, 1.96));
    QCOMPARE(win.w.parameterPanel()->undoStack()->count(), undo_before + 1);
    QVERIFY(!win.w.jobs()->IsBusy());  // nothing re-runs
    win.w.parameterPanel()->undoStack()->undo();
    QCOMPARE(scene->SignificantVertices(), Significant(model, 1.96));
    QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join(QLatin1Char('\n'))));
  }

  void objectsTableHeightWithSigma() {
    ObjectsPanel panel;
    panel.setFixedSize(1000, 260);
    const auto mapping = SyntheticMapping();
    panel.SetMapping(mapping);
    const hull::DetectedObject& o = mapping->result->objects.at(0);
    QVERIFY(std::isfinite(o.max_height_sigma));
    QAbstractItemModel* m = panel.objectsTable()->model();
    int max_column = -1, p95_column = -1;
    for (int c = 0; c < m->columnCount(); ++c) {
      const QString h = m->headerData(c, Qt::Horizontal).toString();
      if (h.startsWith(QStringLiteral("Max height ± σ"))) max_column = c;
      if (h.startsWith(QStringLiteral("95th"))) p95_column = c;
    }
    QVERIFY(max_column >= 0 && p95_column >= 0);
    QStringList cells;
    for (int r = 0; r < m->rowCount(); ++r) cells << m->index(r, max_column).data().toString();
    QVERIFY2(cells.contains(HeightWithSigma(o.max_height, o.max_height_sigma)), qPrintable(cells.join(", ")));
    QVERIFY(HeightWithSigma(o.max_height, o.max_height_sigma).contains(QStringLiteral(" ± ")));
  }

  void compareTwoResultsFolders() {
    const ComparePair pair = WriteComparePair();
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    QVERIFY(win.w.action(QStringLiteral("compareSurveys")));
    win.w.surveyCompare()->CompareFolders(pair.a, pair.b);
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join(QLatin1Char('\n'))));
    const auto& comparison = win.w.session()->comparison();
    QVERIFY(comparison);
    int grown = 0, removed = 0, added = 0, other = 0;
    for (const hull::ObjectChange& c : comparison->comparison.objects) {
      if (c.kind == hull::ObjectChangeKind::kGrown && c.id_b == pair.first_id) {
        ++grown;
        QVERIFY(std::abs(c.change - 0.05) < 1e-9);
      } else if (c.kind == hull::ObjectChangeKind::kRemoved && c.id_a == pair.second_id) {
        ++removed;
      } else if (c.kind == hull::ObjectChangeKind::kNew && c.id_b == "obj-new") {
        ++added;
      } else if (c.kind != hull::ObjectChangeKind::kUnchanged) {
        ++other;
      }
    }
    QCOMPARE(grown, 1);
    QCOMPARE(removed, 1);
    QCOMPARE(added, 1);
    QCOMPARE(other, 0);
    SceneView* scene = win.w.sceneView();
    QVERIFY(scene->Stats(SceneLayer::kHeightChange).visible);
    QVERIFY(scene->ChangeLegendVisible());
    // Symmetric about 0, to the largest change: the new 8 cm lump or the
    // removed object's hollow in B's heights.
    double largest = 0;
    for (double v : *comparison->comparison.model.FindScalar("change")) largest = std::max(largest, std::abs(v));
    QVERIFY(largest >= 0.08 - 1e-9);
    QVERIFY(std::abs(scene->ChangeLegendRange().second - largest) < 0.02);
    QVERIFY(std::abs(scene->ChangeLegendRange().first + largest) < 0.02);
    SurveyComparePanel* panel = win.w.comparePanel();
    QCOMPARE(panel->table()->model()->rowCount(), static_cast<int>(comparison->comparison.objects.size()));
    QVERIFY(panel->summaryText().contains(QStringLiteral("1 new, 1 grown, 0 shrunk, 1 removed")));
    QVERIFY(panel->isVisible());
    // The whole window, to look at (not compared with a baseline: the docks'
    // sizes follow the platform's fonts).
    Settle(&win.w);
    QVERIFY(win.w.grab().save(OutputDir() + QStringLiteral("/main_window_compare.png")));

    // The views, at fixed sizes.
    SceneView view;
    view.setFixedSize(640, 480);
    const auto& survey = MakeSyntheticSurvey();
    view.SetModelPose(PlacementPose(survey.bundle.get(), ModelPlacement::kTruth));
    view.SetComparison(comparison);
    SceneOptions o = OnlyLayer(SceneLayer::kHeightChange);
    view.SetOptions(o);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    view.ResetCamera();
    Check(view.Grab(), QStringLiteral("scene_height_change"));
    // The folders named without this build's paths, for a baseline that
    // holds on any machine.
    auto named = std::make_shared<hull::SurveyComparisonRun>(*comparison);
    named->folder_a = "survey-a/mapping";
    named->folder_b = "survey-b/mapping";
    SurveyComparePanel shown;
    shown.setFixedSize(900, 260);
    shown.SetComparison(named);
    shown.show();
    QVERIFY(QTest::qWaitForWindowExposed(&shown));
    Settle(&shown);
    const QImage table = shown.grab().toImage();
    table.save(OutputDir() + QStringLiteral("/view_change_table_raw.png"));
    Check(table, QStringLiteral("view_change_table"), 0.03);
  }

  void compareWithTheMappingOnScreen() {
    const ComparePair pair = WriteComparePair();
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    const auto& survey = MakeSyntheticSurvey();
    QVERIFY(!win.w.surveyCompare()->CanCompareWithMapping());
    win.w.session()->SetMesh({QStringLiteral("synthetic-hull.ply"), survey.mesh});
    win.w.session()->SetMapping(SyntheticMapping());
    QVERIFY(win.w.surveyCompare()->CanCompareWithMapping());
    // A's folder holds the same mapping as the one on screen: nothing changed.
    win.w.surveyCompare()->CompareWithMapping(pair.a);
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join(QLatin1Char('\n'))));
    const auto& comparison = win.w.session()->comparison();
    QVERIFY(comparison);
    QCOMPARE(comparison->comparison.objects.size(), SyntheticMapping()->result->objects.size());
    for (const hull::ObjectChange& c : comparison->comparison.objects) {
      QCOMPARE(c.kind, hull::ObjectChangeKind::kUnchanged);
      QVERIFY(std::abs(c.change) < 1e-12);
    }
    QCOMPARE(comparison->comparison.significant_vertices, std::size_t(0));
    QVERIFY(win.w.sceneView()->Stats(SceneLayer::kHeightChange).visible);
  }

  void compareRefusesAFolderWithoutResults() {
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    win.w.surveyCompare()->CompareFolders(OutputDir(), OutputDir());
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    QVERIFY(!win.w.session()->comparison());
    QCOMPARE(win.errors.size(), 1);
    QVERIFY2(win.errors.front().contains(QStringLiteral("neither mapping results")), qPrintable(win.errors.front()));
  }

 private:
  void Check(const QImage& image, const QString& name, double max_fraction = 0.01) {
    QString message;
    if (!MatchesBaseline(image, name, &message, 40, max_fraction)) QFAIL(qPrintable(message));
  }
};

HI_GUI_TEST_MAIN(TrustViewsTest)
#include "results/compare_files.h"
#include "results/mapping_files.h"
#include "trust_views_test.moc"
