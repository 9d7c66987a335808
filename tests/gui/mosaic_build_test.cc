// Inspection > Build photomosaic in the main window, on a small rendered
// version 2 survey (the demo preset's monocular rig at a quarter of the
// HAUV's resolution, 340x256, over 1.5 m of the keel, 6 keyframes, with its
// features.csv). First with results made from its truth (the true poses as
// the adjustment and the core Mapper's remeshed model of them): the action
// is disabled until there are results; building runs in a job with rising
// progress, writes the results folder (the results, mosaic/ with OBJ, MTL,
// atlas, PLY; the user's own file kept), shows the textured layer (looked
// at: textured, no black) and hands mosaic.ply to the report hook; the
// parameter panel's Photomosaic group sets the next build's options, with
// undo; cancel leaves the previous folder byte for byte. Then the whole way
// (Inspection > Run in the window, then the build). Finally the refusals:
// a file, a folder below a file, another survey's results, images missing
// since opening, no results, a survey without images — each a message
// naming the reason and the path, nothing written, no crash.
#include <QAbstractButton>
#include <QAction>
#include <QApplication>
#include <QCryptographicHash>
#include <QDialog>
#include <QDockWidget>
#include <QFile>
#include <QFileDialog>
#include <QMessageBox>
#include <QScrollArea>
#include <QSignalSpy>
#include <QTimer>
#include <QUndoStack>
#include <QtTest>
#include <filesystem>
#include <fstream>
#include <memory>

#include "base/file_io.h"
#include "base/progress.h"
#include "gui_test_support.h"
#include "inspection_window.h"
#include "mapping/mapper.h"
#include "mosaic/mosaic_io.h"
#include "results/adjustment_files.h"
#include "simulate/survey_simulator.h"
#include "synthetic_survey.h"
#include "ui/controllers/mosaic_controller.h"
#include "ui/session/inspection_results.h"
#include "ui/session/mosaic_layer.h"
#include "ui/views/scene_view.h"

namespace hull::ui {
namespace {

namespace fs = std::filesystem;
using testing::OutputDir;
using testing::Window;

std::string Native(const QString& path) { return QFile::encodeName(path).toStdString(); }

const QString& SurveyDir() {
  static const QString dir = [] {
    const QString d = OutputDir() + QStringLiteral("/mosaic_build_survey_%1").arg(QCoreApplication::applicationPid());
    QDir(d).removeRecursively();
    SurveySimulationOptions o = SurveyPreset("demo");
    o.camera = CameraType::kMono;
    o.camera_scale = 0.25;
    o.plan.start = 40.0;
    o.plan.end = 41.5;
    o.plan.half_width = 0.3;
    o.images = true;
    NullProgress progress;
    WriteSimulatedSurvey(SimulateSurvey(o, progress), Native(d));
    return d;
  }();
  return dir;
}

// The open survey's truth as the results on screen: alignment, adjustment
// (true poses, servo angles, extrinsic and model pose) and the Mapper's
// remeshed model of them.
void PutTruthResults(Session& session) {
  const SurveyBundle& b = *session.survey()->bundle;
  const TriangleMesh& cad = *session.mesh()->mesh;
  auto alignment = std::make_shared<ModelAlignment>();
  alignment->x_gM = alignment->initial_x_gM = Pose::FromVector(b.truth->x_gM);
  auto r = std::make_shared<AdjustmentResult>();
  for (const TruePose& p : b.truth->poses) {
    r->keyframes.push_back(p.keyframe);
    r->poses.push_back(p.x_gv);
    r->servo.push_back(p.servo);
  }
  r->x_gM = r->x_gM_initial = b.truth->x_gM;
  r->x_s_cT = b.truth->x_s_cT;
  r->bundle_path = Native(session.survey()->path);
  r->mesh_path = Native(session.mesh()->path);
  for (const TrueLandmark& l : b.truth->landmarks) {
    LandmarkEstimate e;
    e.id = l.landmark;
    e.p = l.p;
    e.deviation = l.deviation;
    e.label = l.object.empty() ? 1 : 0;
    r->landmarks.push_back(e);
  }
  r->converged = true;
  auto run = std::make_shared<AdjustmentRun>();
  run->key = "truth";
  run->overlays = std::make_shared<const AdjustedOverlays>(ComputeAdjustedOverlays(b, *r));
  run->result = r;

  Mapper mapper(MappingInputFromTruth(b), cad);
  NullProgress progress;
  auto mapping = std::make_shared<MappingRun>();
  auto result = std::make_shared<const MappingResult>(mapper.Run(MappingOptions(), progress));
  mapping->key = "truth-map";
  mapping->adjustment_key = run->key;
  mapping->input = std::make_shared<const MappingInput>(mapper.input());
  mapping->overlays = std::make_shared<const MappingOverlays>(ComputeMappingOverlays(*result, cad));
  mapping->result = std::move(result);

  session.SetAlignment(alignment);
  session.SetAdjustment(run);
  session.SetMapping(mapping);
}

bool OpenWithResults(Window& win) {
  if (!QTest::qWaitForWindowExposed(&win.w)) return false;
  win.w.OpenPaths({SurveyDir()});
  if (!QTest::qWaitFor([&win] { return !win.w.jobs()->IsBusy() && win.w.session()->mesh(); }, 120000)) return false;
  if (win.w.action(QStringLiteral("buildMosaic"))->isEnabled()) return false;  // no results yet
  PutTruthResults(*win.w.session());
  return true;
}

QByteArray FileHash(const fs::path& p) {
  QFile f(QString::fromStdString(p.string()));
  if (!f.open(QIODevice::ReadOnly)) return {};
  return QCryptographicHash::hash(f.readAll(), QCryptographicHash::Sha256);
}

// Every file under `dir` (relative path) with its hash.
std::map<std::string, QByteArray> Snapshot(const fs::path& dir) {
  std::map<std::string, QByteArray> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = FileHash(e.path());
  }
  return files;
}

// Builds through the menu action, answering its folder dialog with
// `folder` (which must exist, as in the dialog).
// Chooses `folder` in the file dialog; a folder of other files is then
// confirmed in the question that follows (returned: whether it was asked).
bool TriggerBuild(Window& win, const QString& folder) {
  if (!QDir(folder).exists()) return false;
  auto asked = std::make_shared<bool>(false);
  QTimer::singleShot(300, [folder, asked] {
    auto* dialog = qobject_cast<QFileDialog*>(QApplication::activeModalWidget());
    if (!dialog) return;
    // The folder itself as the dialog's directory, nothing selected in it:
    // what accept() returns (selectFile would select it in its parent, once
    // the parent's listing has loaded).
    dialog->setDirectory(folder);
    QTimer::singleShot(300, [asked] {
      auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
      if (!box) return;
      *asked = box->text().contains(QStringLiteral("holds files HullInspect did not write"));
      box->button(QMessageBox::Yes)->click();
    });
    static_cast<QDialog*>(dialog)->accept();  // QFileDialog::accept: the selected folder
  });
  win.w.action(QStringLiteral("buildMosaic"))->trigger();
  return *asked;
}

// The mosaic layer alone in the 3-D view (docks hidden), seen from the
// vehicle's side of the surveyed stretch, grabbed.
QImage ShowTheMosaicAlone(Window& win) {
  SceneOptions o = win.w.sceneView()->options();
  for (SceneLayer layer : AllSceneLayers()) o.visible[layer] = layer == SceneLayer::kPhotomosaic;
  win.w.sceneView()->SetOptions(o);
  const SurveyBundle& b = *win.w.session()->bundle();
  Eigen::Vector3d landmarks = Eigen::Vector3d::Zero(), vehicle = Eigen::Vector3d::Zero();
  for (const TrueLandmark& l : b.truth->landmarks) landmarks += l.p;
  landmarks /= static_cast<double>(b.truth->landmarks.size());
  for (const TruePose& p : b.truth->poses) vehicle += p.x_gv.head<3>();
  vehicle /= static_cast<double>(b.truth->poses.size());
  const Eigen::Vector3d along = b.truth->poses.back().x_gv.head<3>() - b.truth->poses.front().x_gv.head<3>();
  CameraState c;
  c.focal_point = {landmarks.x(), landmarks.y(), landmarks.z()};
  const Eigen::Vector3d eye = landmarks + 1.6 * (vehicle - landmarks);
  c.position = {eye.x(), eye.y(), eye.z()};
  c.view_up = {along.x(), along.y(), along.z()};
  c.view_angle = 40;
  for (QDockWidget* dock : win.w.findChildren<QDockWidget*>()) dock->hide();  // the 3-D view alone, large
  win.w.sceneView()->SetCamera(c);
  testing::Settle(&win.w);
  QTest::qWait(200);
  testing::Settle(&win.w);
  return win.w.sceneView()->Grab();
}

}  // namespace

class MosaicBuildTest : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() { QVERIFY(!SurveyDir().isEmpty()); }
  void cleanupTestCase() { QDir(SurveyDir()).removeRecursively(); }

  void buildsShowsAndCancelKeepsThePreviousFolder() {
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    QAction* build = win.w.action(QStringLiteral("buildMosaic"));
    QVERIFY(build && !build->isEnabled());
    QVERIFY(win.w.mosaicBuilder()->Unavailable().contains(QStringLiteral("Open a survey")));
    QVERIFY(OpenWithResults(win));
    QVERIFY2(build->isEnabled(), qPrintable(win.w.mosaicBuilder()->Unavailable()));

    const QString results = OutputDir() + QStringLiteral("/mosaic_build_results");
    QDir(results).removeRecursively();
    QVERIFY(QDir().mkpath(results));
    {
      std::ofstream mine(Native(results + QStringLiteral("/notes.txt")));
      mine << "the user's own file\n";
    }
    QSignalSpy progress(win.w.jobs(), &JobRunner::jobProgress);
    QElapsedTimer timer;
    timer.start();
    // The folder holds a file of the user's: asked first, then written beside it.
    QVERIFY(TriggerBuild(win, results));
    QTRY_VERIFY_WITH_TIMEOUT(win.w.jobs()->IsBusy(MosaicController::kMosaicJob), 5000);
    QVERIFY(!build->isEnabled());  // one build at a time
    HI_WAIT_IDLE(win.w.jobs(), 240000);
    const double seconds = timer.elapsed() / 1000.0;
    QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join('\n')));
    // Progress moved: many updates, rising, to the end.
    std::vector<double> fractions;
    for (const auto& p : progress) {
      if (p.at(1).toString() == MosaicController::kMosaicJob) fractions.push_back(p.at(2).toDouble());
    }
    QVERIFY2(fractions.size() >= 5, qPrintable(QString::number(fractions.size())));
    for (std::size_t i = 1; i < fractions.size(); ++i) QVERIFY(fractions[i] >= fractions[i - 1] - 1e-9);
    QVERIFY(fractions.front() < 0.05 && fractions.back() > 0.99);

    // The results folder: the session's results, the mosaic, the user's file.
    const fs::path root(Native(results));
    for (const char* f : {"summary.json", "alignment.json", "adjustment/adjustment.json", "mapping/model.ply",
                          "mosaic/mosaic.obj", "mosaic/mosaic.mtl", "mosaic/mosaic_atlas.png", "mosaic/mosaic.ply",
                          "mosaic/mosaic.json", "mosaic/mosaic_faces.csv", "notes.txt"}) {
      QVERIFY2(fs::is_regular_file(root / f), f);
    }
    // The layer on screen, placed and visible, the hull and heatmap switched off.
    const auto& mosaic = win.w.session()->mosaic();
    QVERIFY(mosaic);
    QCOMPARE(fs::path(mosaic->dir).lexically_normal(), (root / "mosaic").lexically_normal());
    QCOMPARE(mosaic->adjustment_key, std::string("truth"));
    const SceneView::LayerStats stats = win.w.sceneView()->Stats(SceneLayer::kPhotomosaic);
    QVERIFY(stats.present && stats.visible);
    QCOMPARE(stats.cells, static_cast<long long>(mosaic->faces));
    QVERIFY(!win.w.sceneView()->Stats(SceneLayer::kHeatmap).visible);
    // The report hook has the mosaic's per-vertex colour.
    const auto report = win.w.CollectReport();
    QVERIFY(report && report->mosaic == mosaic->coloured && report->mosaic);
    QVERIFY(report->mosaic->FindScalar("red"));
    QCOMPARE(report->mosaic_path, (root / "mosaic" / "mosaic.ply").string());
    // What the mosaic says of itself.
    const std::string summary = ReadFileToString((root / "mosaic" / "mosaic.json").string());
    qInfo("GUI build: %.1f s (%zu progress updates); %zu faces, mosaic.json %zu bytes", seconds, fractions.size(),
          mosaic->faces, summary.size());

    // Look at it: the textured stretch from the vehicle's side.
    const QImage shot = ShowTheMosaicAlone(win);
    QVERIFY(!shot.isNull());
    QVERIFY(shot.save(OutputDir() + QStringLiteral("/mosaic_build_scene.png")));
    // docs/images/scene-photomosaic-built.png (the user guide's figure).
    QVERIFY(shot.scaledToWidth(720, Qt::SmoothTransformation)
                .save(OutputDir() + QStringLiteral("/scene-photomosaic-built.png")));
    // Mostly textured: the middle third of the view is the hull's paint, not
    // the background and not black.
    const QColor background = shot.pixelColor(2, 2);
    int textured = 0, black = 0, total = 0;
    for (int y = shot.height() / 3; y < 2 * shot.height() / 3; y += 4) {
      for (int x = shot.width() / 3; x < 2 * shot.width() / 3; x += 4) {
        const QColor px = shot.pixelColor(x, y);
        ++total;
        if (px.value() < 12) ++black;
        if (std::abs(px.red() - background.red()) + std::abs(px.green() - background.green()) +
                std::abs(px.blue() - background.blue()) >
            30)
          ++textured;
      }
    }
    qInfo("centre of the view: %d of %d samples textured, %d black", textured, total, black);
    QVERIFY(textured > total * 0.8);
    QVERIFY(black < total * 0.02);

    // Cancel a second build (other options: it would write another atlas):
    // the folder stays byte for byte, the layer stays.
    const auto before = Snapshot(root);
    // The Photomosaic group of the parameter panel sets the next build's
    // options; undo brings the previous value back.
    QCOMPARE(win.w.mosaicBuilder()->options().texel_size, MosaicOptions().texel_size);
    win.Real("mosaic_texel_size")->setValue(0.006);
    QCOMPARE(win.w.mosaicBuilder()->options().texel_size, 0.006);
    win.w.parameterPanel()->undoStack()->undo();
    QCOMPARE(win.w.mosaicBuilder()->options().texel_size, MosaicOptions().texel_size);
    QVERIFY(!win.w.jobs()->IsBusy());  // nothing re-runs
    win.Real("mosaic_texel_size")->setValue(0.008);
    QCOMPARE(win.w.mosaicBuilder()->options().texel_size, 0.008);
    {  // The group as the user sees it (looked at).
      ParameterPanel* panel = win.w.parameterPanel();
      auto* dock = qobject_cast<QDockWidget*>(panel->parentWidget());
      QVERIFY(dock);
      dock->setFloating(true);
      dock->resize(420, 700);
      dock->show();
      if (auto* scroll = panel->findChild<QScrollArea*>())
        scroll->ensureWidgetVisible(panel->editor(QStringLiteral("mosaic_normalisation")));
      testing::Settle(dock);
      QVERIFY(panel->grab().save(OutputDir() + QStringLiteral("/mosaic_build_parameters.png")));
      dock->hide();
    }
    QSignalSpy cancelled(win.w.jobs(), &JobRunner::jobCancelled);
    progress.clear();
    TriggerBuild(win, results);
    QTRY_VERIFY_WITH_TIMEOUT(
        [&] {
          for (const auto& p : progress) {
            if (p.at(1).toString() == MosaicController::kMosaicJob && p.at(2).toDouble() > 0.1) return true;
          }
          return false;
        }(),
        120000);
    win.w.action(QStringLiteral("cancelJobs"))->trigger();
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    QCOMPARE(cancelled.size(), 1);
    QCOMPARE(cancelled.first().at(1).toString(), MosaicController::kMosaicJob);
    QVERIFY(Snapshot(root) == before);
    for (const auto& e : fs::directory_iterator(root.parent_path())) {
      QVERIFY2(e.path().filename().string().find("mosaic_build_results.writing") == std::string::npos,
               e.path().c_str());
    }
    QVERIFY(win.w.session()->mosaic() == mosaic);
    QVERIFY(win.errors.isEmpty());
    QVERIFY(build->isEnabled());
  }

  // The whole way: the inspection run here (alignment, adjustment from the
  // bundle's feature tracks, mapping), then the build.
  void buildsFromTheInspectionRunHere() {
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    win.w.OpenPaths({SurveyDir()});
    QTRY_VERIFY_WITH_TIMEOUT(!win.w.jobs()->IsBusy() && win.w.session()->mesh(), 120000);
    QAction* build = win.w.action(QStringLiteral("buildMosaic"));
    QVERIFY(!build->isEnabled());
    QElapsedTimer timer;
    timer.start();
    win.w.action(QStringLiteral("runInspection"))->trigger();
    QTRY_VERIFY_WITH_TIMEOUT(win.w.session()->mapping() && !win.w.jobs()->IsBusy(), 600000);
    const double run_seconds = timer.elapsed() / 1000.0;
    QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join('\n')));
    QVERIFY2(build->isEnabled(), qPrintable(win.w.mosaicBuilder()->Unavailable()));
    const QString results = OutputDir() + QStringLiteral("/mosaic_build_run_results");
    QDir(results).removeRecursively();
    QVERIFY(QDir().mkpath(results));
    timer.restart();
    QVERIFY(!TriggerBuild(win, results));  // an empty folder: nothing to ask
    QTRY_VERIFY_WITH_TIMEOUT(win.w.jobs()->IsBusy(MosaicController::kMosaicJob), 5000);
    HI_WAIT_IDLE(win.w.jobs(), 240000);
    QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join('\n')));
    const auto& mosaic = win.w.session()->mosaic();
    QVERIFY(mosaic && mosaic->adjustment_key == win.w.session()->adjustment()->key);
    QVERIFY(win.w.sceneView()->Stats(SceneLayer::kPhotomosaic).visible);
    const fs::path root(Native(results));
    QVERIFY(fs::is_regular_file(root / "mosaic" / "mosaic_atlas.png"));
    QVERIFY(fs::is_regular_file(root / "adjustment" / "adjustment.json"));
    // The adjustment written is the one on screen: the mosaic opens from the folder as built.
    const MosaicLayer reopened = LoadMosaicLayer(Native(results));
    QVERIFY((reopened.x_gM.ToVector() - win.w.session()->adjustment()->result->x_gM).norm() < 1e-9);
    QVERIFY(win.w.CollectReport()->mosaic == mosaic->coloured);
    qInfo("inspection run %.1f s, then the GUI build %.1f s", run_seconds, timer.elapsed() / 1000.0);
    // summary.json names the model where it lies, not where it was written.
    const std::string summary = ReadFileToString((root / "summary.json").string());
    QVERIFY2(summary.find((root / "mapping" / "model.ply").string()) != std::string::npos, summary.c_str());
    QVERIFY2(summary.find(".writing-") == std::string::npos, summary.c_str());
    const QImage shot = ShowTheMosaicAlone(win);
    QVERIFY(!shot.isNull() && shot.save(OutputDir() + QStringLiteral("/mosaic_build_run_scene.png")));
  }

  void errorsAreMessagesNamingThePath() {
    Window win;
    QVERIFY(OpenWithResults(win));
    MosaicController* builder = win.w.mosaicBuilder();
    const QString base = OutputDir() + QStringLiteral("/mosaic_build_errors");
    QDir(base).removeRecursively();
    QVERIFY(QDir().mkpath(base));
    const QString file = base + QStringLiteral("/a-file");
    {
      std::ofstream f(Native(file));
      f << "x";
    }
    auto expect = [&](const QString& folder, const QString& words, bool force = false) {
      win.errors.clear();
      builder->Build(folder, force);
      if (!QTest::qWaitFor([&win] { return !win.w.jobs()->IsBusy(); }, 240000)) return QStringLiteral("still busy");
      if (win.errors.size() != 1) return QStringLiteral("%1 errors for %2").arg(win.errors.size()).arg(folder);
      if (!win.errors.first().contains(words)) return win.errors.first();
      return QString();
    };
    // A file, and a folder below a file (cannot be created).
    QString e = expect(file, QStringLiteral("is a file"));
    QVERIFY2(e.isEmpty(), qPrintable(e));
    e = expect(file + QStringLiteral("/results"), QStringLiteral("a-file"));
    QVERIFY2(e.isEmpty(), qPrintable(e));
    // Another survey's results.
    const QString other = base + QStringLiteral("/other");
    AdjustmentResult a;
    a.bundle_path = Native(base + QStringLiteral("/another-bundle"));
    WriteAdjustmentResult(a, Native(other + QStringLiteral("/adjustment")));
    e = expect(other, QStringLiteral("HullInspect did not write"));  // no manifest: not confirmed
    QVERIFY2(e.isEmpty(), qPrintable(e));
    e = expect(other, QStringLiteral("another survey"), true);
    QVERIFY2(e.isEmpty(), qPrintable(e));
    QVERIFY(!fs::exists(Native(other + QStringLiteral("/mosaic"))));
    // Images gone since the survey was opened: named, nothing written.
    const fs::path images = fs::path(Native(SurveyDir())) / "images";
    const fs::path hidden = fs::path(Native(SurveyDir())) / "images-hidden";
    fs::rename(images, hidden);
    const QString fresh = base + QStringLiteral("/fresh");
    e = expect(fresh, QStringLiteral("no such image"));
    fs::rename(hidden, images);
    QVERIFY2(e.isEmpty(), qPrintable(e));
    QVERIFY(!fs::exists(Native(fresh + QStringLiteral("/mosaic"))));
    QVERIFY(!win.w.session()->mosaic());
    // Without results: refused with the reason, no job.
    win.w.session()->ClearResults();
    QVERIFY(!win.w.action(QStringLiteral("buildMosaic"))->isEnabled());
    e = expect(fresh, QStringLiteral("Run the inspection first"));
    QVERIFY2(e.isEmpty(), qPrintable(e));
    // A survey without camera images (version 1): refused for that.
    const testing::SyntheticSurvey& v1 = testing::MakeSyntheticSurvey();
    QVERIFY(!v1.bundle->images || v1.bundle->images->present() == 0);
    win.w.session()->SetSurvey(LoadedSurvey{QStringLiteral("synthetic"), v1.bundle,
                                            std::make_shared<const SurveyOverlays>(ComputeSurveyOverlays(*v1.bundle))});
    e = expect(fresh, QStringLiteral("no camera images"));
    QVERIFY2(e.isEmpty(), qPrintable(e));
  }
};

}  // namespace hull::ui

HI_GUI_TEST_MAIN(hull::ui::MosaicBuildTest)
#include "mosaic_build_test.moc"
