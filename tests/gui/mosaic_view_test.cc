// The photomosaic in the 3-D view: a tiny mosaic folder written here (two
// quads textured from the red and the blue half of an atlas, in a results
// folder whose adjustment places the model), opened through the main
// window's document controller; the layer is listed, visible, placed by the
// adjustment's x_gM and shows the atlas's colours where its quads are.
#include <QCheckBox>
#include <QColor>
#include <QImage>
#include <QtTest>
#include <filesystem>
#include <fstream>

#include "adjust/adjust_result.h"
#include "base/error.h"
#include "geometry/mesh_io.h"
#include "gui_test_support.h"
#include "inspection_window.h"
#include "results/adjustment_files.h"
#include "ui/controllers/document_controller.h"
#include "ui/panels/layers_panel.h"
#include "ui/session/mosaic_layer.h"
#include "ui/views/scene_view.h"

namespace hull::ui {
namespace {

namespace fs = std::filesystem;
using testing::OutputDir;

// x_gM of the tiny results: away from the origin and turned, so that a
// layer drawn unplaced would miss the sample points.
const Vector6d& TinyPose() {
  static const Vector6d x = (Vector6d() << 0.6, -0.3, 1.5, 0.0, 0.0, 0.4).finished();
  return x;
}

// RESULTS/adjustment (x_gM only), RESULTS/mapping/model.ply and
// RESULTS/mosaic: the unit square in M's xy-plane as two quads, the left
// one (x < 0.5) textured from the atlas's red half, the right one from its
// blue half.
std::string WriteTinyResults(const std::string& name) {
  const fs::path root = fs::path(OutputDir().toStdString()) / name;
  fs::remove_all(root);
  fs::create_directories(root / "mapping");
  fs::create_directories(root / "mosaic");
  AdjustmentResult adjustment;
  adjustment.x_gM = TinyPose();
  adjustment.x_gM_initial = TinyPose();
  WriteAdjustmentResult(adjustment, (root / "adjustment").string());
  TriangleMesh model;
  model.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  model.faces = {{0, 1, 2}, {0, 2, 3}};
  model.ComputeNormals();
  SaveMesh(model, (root / "mapping" / "model.ply").string());

  QImage atlas(16, 8, QImage::Format_RGB888);
  for (int y = 0; y < atlas.height(); ++y) {
    for (int x = 0; x < atlas.width(); ++x)
      atlas.setPixelColor(x, y, x < 8 ? QColor(220, 30, 30) : QColor(30, 40, 220));
  }
  if (!atlas.save(QString::fromStdString((root / "mosaic" / "mosaic_atlas.png").string()))) return {};
  std::ofstream obj(root / "mosaic" / "mosaic.obj");
  obj << "mtllib mosaic.mtl\n"
         "v 0 0 0\nv 0.5 0 0\nv 1 0 0\nv 0 1 0\nv 0.5 1 0\nv 1 1 0\n"
         "vt 0.1 0.2\nvt 0.4 0.2\nvt 0.4 0.8\nvt 0.1 0.8\n"  // inside the red half
         "vt 0.6 0.2\nvt 0.9 0.2\nvt 0.9 0.8\nvt 0.6 0.8\n"  // inside the blue half
         "usemtl mosaic\n"
         "f 1/1 2/2 5/3\nf 1/1 5/3 4/4\n"
         "f 2/5 3/6 6/7\nf 2/5 6/7 5/8\n";
  std::ofstream mtl(root / "mosaic" / "mosaic.mtl");
  mtl << "newmtl mosaic\nKd 1 1 1\nmap_Kd mosaic_atlas.png\n";
  return root.string();
}

bool Reddish(const QColor& c) { return c.red() > 120 && c.red() > 2 * c.blue() && c.red() > 2 * c.green(); }
bool Bluish(const QColor& c) { return c.blue() > 120 && c.blue() > 2 * c.red() && c.blue() > 2 * c.green(); }

}  // namespace

class MosaicViewTest : public QObject {
  Q_OBJECT

 private slots:
  void loadsFromAResultsOrMosaicFolder() {
    const std::string results = WriteTinyResults("tiny-mosaic-load");
    QVERIFY(!results.empty());
    for (const std::string& folder : {results, results + "/mosaic"}) {
      const MosaicLayer layer = LoadMosaicLayer(folder);
      QCOMPARE(layer.faces, std::size_t{4});
      QCOMPARE(layer.vertices, std::size_t{6});
      QVERIFY((layer.x_gM.translation() - Eigen::Vector3d(0.6, -0.3, 1.5)).norm() < 1e-9);
      QVERIFY(fs::path(layer.atlas).filename() == "mosaic_atlas.png");
    }
    // A folder without a mosaic, and a mosaic without its atlas: errors naming the folder.
    try {
      LoadMosaicLayer(results + "/mapping");
      QFAIL("no error for a folder without a mosaic");
    } catch (const InputError& e) {
      QVERIFY2(std::string(e.what()).find("holds no photomosaic") != std::string::npos, e.what());
      QVERIFY2(std::string(e.what()).find("mapping") != std::string::npos, e.what());
    }
    fs::remove(fs::path(results) / "mosaic" / "mosaic_atlas.png");
    try {
      LoadMosaicLayer(results);
      QFAIL("no error for a mosaic without its atlas");
    } catch (const InputError& e) {
      QVERIFY2(std::string(e.what()).find("mosaic_atlas.png") != std::string::npos, e.what());
    }
  }

  void showsTheTexturedLayer() {
    const std::string results = WriteTinyResults("tiny-mosaic-view");
    QVERIFY(!results.empty());
    testing::Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    SceneView* scene = win.w.sceneView();
    QVERIFY(!scene->Stats(SceneLayer::kPhotomosaic).present);
    QCheckBox* check = win.w.layersPanel()->layerCheckBox(SceneLayer::kPhotomosaic);
    QVERIFY(check);
    QVERIFY(!check->isEnabled());

    win.w.documents()->OpenMosaic(QString::fromStdString(results));
    QTRY_VERIFY_WITH_TIMEOUT(win.w.session()->mosaic() != nullptr, 20000);
    HI_WAIT_IDLE(win.w.jobs(), 20000);
    QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join(QLatin1Char('\n'))));
    const SceneView::LayerStats stats = scene->Stats(SceneLayer::kPhotomosaic);
    QVERIFY(stats.present);
    QVERIFY(stats.visible);
    QCOMPARE(stats.cells, 4LL);
    QVERIFY(check->isEnabled());
    QVERIFY(check->isChecked());

    testing::Settle(&win.w);
    const QImage shot = scene->Grab();
    QVERIFY(!shot.isNull());
    QVERIFY(shot.save(OutputDir() + QStringLiteral("/scene_photomosaic.png")));
    const Pose x_gM = Pose::FromVector(TinyPose());
    const auto left = scene->WidgetPosition(x_gM * Eigen::Vector3d(0.25, 0.5, 0));
    const auto right = scene->WidgetPosition(x_gM * Eigen::Vector3d(0.75, 0.5, 0));
    QVERIFY(left && right);
    const QColor l = shot.pixelColor(*left), r = shot.pixelColor(*right);
    QVERIFY2(Reddish(l), qPrintable(QStringLiteral("left quad %1").arg(l.name())));
    QVERIFY2(Bluish(r), qPrintable(QStringLiteral("right quad %1").arg(r.name())));

    // Switched off in the layers panel: gone from the picture.
    check->setChecked(false);
    QVERIFY(!scene->Stats(SceneLayer::kPhotomosaic).visible);
    testing::Settle(&win.w);
    const QImage off = scene->Grab();
    QVERIFY(!Reddish(off.pixelColor(*left)));
    QVERIFY(!Bluish(off.pixelColor(*right)));

    // A folder without a mosaic: an error naming it, the mosaic stays.
    win.w.documents()->OpenMosaic(QString::fromStdString(results + "/mapping"));
    HI_WAIT_IDLE(win.w.jobs(), 20000);
    QTRY_VERIFY_WITH_TIMEOUT(!win.errors.isEmpty(), 5000);
    QVERIFY2(win.errors.join(QLatin1Char('\n')).contains(QStringLiteral("holds no photomosaic")),
             qPrintable(win.errors.join(QLatin1Char('\n'))));
    QVERIFY(scene->Stats(SceneLayer::kPhotomosaic).present);
  }
};

}  // namespace hull::ui

HI_GUI_TEST_MAIN(hull::ui::MosaicViewTest)
#include "mosaic_view_test.moc"
