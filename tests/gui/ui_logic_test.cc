// The GUI's logic without windows: sensor frames of the overlays checked
// against the survey's ground truth, pick details, the demo cache, project
// files, the command line and the sorting of opened paths.
#include <QDir>
#include <QFile>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "base/error.h"
#include "geometry/mesh_index.h"
#include "gui_test_support.h"
#include "ui/app/command_line.h"
#include "ui/controllers/document_controller.h"
#include "ui/models/deviation_histogram.h"
#include "ui/models/pick_details.h"
#include "ui/models/scale_bar.h"
#include "ui/session/demo_cache.h"
#include "ui/session/inspection_parameters.h"
#include "ui/session/mosaic_layer.h"
#include "ui/session/project_file.h"
#include "ui/session/session.h"

using namespace hull::ui;
using hull::ui::testing::LoadDemo;

namespace {

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// Cancels at the first update.
class CancelAtOnce final : public hull::Progress {
 public:
  void Update(double, const std::string&) override { cancelled_ = true; }
  bool Cancelled() const override { return cancelled_; }

 private:
  bool cancelled_ = false;
};

void WriteText(const QString& path, const QByteArray& text) {
  QFile f(path);
  QVERIFY(f.open(QIODevice::WriteOnly));
  f.write(text);
}

QByteArray ReadText(const QString& path) {
  QFile f(path);
  return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

// The project fuzz harness's seeds (tests/fuzz/corpus/project): projects as
// the GUI saves them, each relative to the folder `dir` of its file.
// A view a user changed: the placement, every kind of scene setting and the
// camera away from their defaults.
void ChangeViewAsAUserWould(ProjectData* p) {
  p->placement = QStringLiteral("guess");
  p->scene.visible[SceneLayer::kDvlHits] = false;
  p->scene.visible[SceneLayer::kFrusta] = true;
  p->scene.hull_edges = true;
  p->scene.colouring = LandmarkColouring::kDeviation;
  p->scene.auto_range = false;
  p->scene.range_min = -0.02;
  p->scene.range_max = 0.2;
  p->scene.tolerance = 0.025;
  p->scene.frustum_stride = 4;
  p->camera = CameraState{{{1.5, -2, 12.25}}, {{0.5, 0.25, 9}}, {{0, 1, 0}}, 25.0};
}

std::vector<std::pair<QString, ProjectData>> ProjectSeeds(const QString& dir) {
  std::vector<std::pair<QString, ProjectData>> seeds;
  ProjectData empty;  // "Save project" with nothing open
  empty.parameters = DefaultValues(DefaultParameterTable());
  seeds.emplace_back(QStringLiteral("defaults.hiproj"), empty);

  ProjectData p = empty;  // an inspection: inputs below the project, view and parameters changed
  p.mesh_path = dir + QStringLiteral("/models/hull.ply");
  p.bundle_path = dir + QStringLiteral("/surveys/day-1");
  p.parameters.insert(QStringLiteral("sigma1"), 0.035);
  p.parameters.insert(QStringLiteral("dbscan_min_points"), 7);
  p.parameters.insert(QStringLiteral("fe_window"), 80.0);
  ChangeViewAsAUserWould(&p);
  seeds.emplace_back(QStringLiteral("inspection.hiproj"), p);

  ProjectData q = empty;  // saved inside the survey folder, the mesh beside it; every layer off
  q.mesh_path = QDir::cleanPath(dir + QStringLiteral("/../cad/hull.stl"));
  q.bundle_path = dir;
  q.parameters.insert(QStringLiteral("model"), QStringLiteral("naive"));
  q.parameters.insert(QStringLiteral("lookup"), QStringLiteral("nearest-vertex"));
  q.parameters.insert(QStringLiteral("fe_clahe"), QStringLiteral("off"));
  q.parameters.insert(QStringLiteral("rejection_rounds"), 0);
  q.placement = QStringLiteral("adjusted");
  for (SceneLayer layer : AllSceneLayers()) q.scene.visible[layer] = false;
  q.scene.frustum_stride = 1;
  q.camera = CameraState{{{0, 0, -30}}, {{0, 0, 0}}, {{1, 0, 0}}, 60.0};
  seeds.emplace_back(QStringLiteral("survey-folder.hiproj"), q);
  return seeds;
}

}  // namespace

class UiLogicTest : public QObject {
  Q_OBJECT

 private slots:
  // --- overlays: the contract's sensor chain, checked against the truth ---

  void dvlHitsFromTruePosesLieOnTheTrueHull() {
    const auto& demo = LoadDemo();
    const auto& truth = *demo.bundle->truth;
    const hull::Pose M_from_g = hull::Pose::FromVector(truth.x_gM).Inverse();
    const hull::MeshIndex index(*demo.mesh);
    std::vector<double> distances;
    for (const DvlHit& hit : ComputeDvlHits(*demo.bundle, PoseSource::kTruth)) {
      distances.push_back(std::abs(index.SignedDistance(M_from_g * hit.point)));
    }
    QVERIFY(distances.size() > 500);
    // 3 mm range noise; a few beams hit foreign objects (up to ~15 cm high).
    const double median = Median(distances);
    QVERIFY2(median < 0.006, qPrintable(QStringLiteral("median |distance| %1 m").arg(median)));
  }

  void trueLandmarksProjectOntoTheirObservations() {
    const auto& demo = LoadDemo();
    hull::SurveyManifest manifest = demo.bundle->manifest;
    manifest.camera.servo_to_top = demo.bundle->truth->x_s_cT;  // the true extrinsic
    std::unordered_map<std::int64_t, const hull::TruePose*> poses;
    for (const auto& p : demo.bundle->truth->poses) poses[p.keyframe] = &p;
    std::unordered_map<std::int64_t, Eigen::Vector3d> landmarks;
    for (const auto& l : demo.bundle->truth->landmarks) landmarks[l.landmark] = l.p;
    std::vector<double> errors;
    for (const auto& f : demo.bundle->features) {
      const auto pose = poses.find(f.keyframe);
      const auto l = landmarks.find(f.landmark);
      if (pose == poses.end() || l == landmarks.end()) continue;
      const hull::Pose x_gc = CameraPose(manifest, pose->second->x_gv, pose->second->servo);
      const Eigen::Vector3d p_c = x_gc.Inverse() * l->second;
      QVERIFY(p_c.z() > 0);
      errors.push_back((manifest.camera.top.Project(p_c) - f.top).norm());
    }
    QVERIFY(errors.size() > 1000);
    const double median = Median(errors);
    QVERIFY2(median < 4.0, qPrintable(QStringLiteral("median reprojection error %1 px").arg(median)));
  }

  void overlaysHoldTheWholeSurvey() {
    const auto& demo = LoadDemo();
    const hull::SurveyBundle& b = *demo.bundle;
    const SurveyOverlays& o = *demo.overlays;
    QCOMPARE(o.trajectory.size(), b.nav.size());
    QCOMPARE(o.true_trajectory.size(), b.truth->poses.size());
    std::size_t returns = 0;
    for (const auto& d : b.dvl) {
      for (double r : d.range) returns += hull::DvlRecord::HasReturn(r);
    }
    QCOMPARE(o.dvl_hits.size(), returns);
    QCOMPARE(o.landmark_source, LandmarkSource::kTruth);
    QCOMPARE(o.landmarks.size(), b.truth->landmarks.size());
    QCOMPARE(o.objects.size(), b.truth->objects.size());
    QVERIFY(o.max_deviation > 0.05);  // the cylinder and the fouling stand off the hull
    for (const auto& l : o.landmarks) QVERIFY(o.bounds.contains(l.position));
    int foreign = 0;
    for (const auto& l : o.landmarks) foreign += l.foreign();
    QVERIFY(foreign > 0 && foreign < static_cast<int>(o.landmarks.size()));
  }

  void frustaReachTheHull() {
    const auto& demo = LoadDemo();
    const auto frusta = ComputeFrusta(*demo.bundle, 10);
    QCOMPARE(frusta.size(), (demo.bundle->nav.size() + 9) / 10);
    const hull::Pose x_gM = PlacementPose(demo.bundle.get(), ModelPlacement::kTruth);
    const hull::MeshIndex index(*demo.mesh);
    std::vector<double> distances;
    for (const auto& f : frusta) {
      const Eigen::Vector3d centre = 0.25 * (f.corners[0] + f.corners[1] + f.corners[2] + f.corners[3]);
      distances.push_back(std::abs(index.SignedDistance(x_gM.Inverse() * centre)));
    }
    // The base of each frustum lies near the hull (initial poses: within tens of cm).
    QVERIFY2(Median(distances) < 0.5, qPrintable(QString::number(Median(distances))));
  }

  void outlinesFollowTheObjects() {
    hull::TrueObject box;
    box.id = "box-1";
    box.kind = hull::ObjectKind::kBox;
    box.center = Eigen::Vector3d(1, 2, 3);
    box.normal = -Eigen::Vector3d::UnitZ();
    box.size = Eigen::Vector3d(0.4, 0.2, 0.1);
    const ObjectOutline o = OutlineOf(box);
    QCOMPARE(o.loops.size(), std::size_t(2));
    QCOMPARE(o.loops[0].size(), std::size_t(4));
    // Side a along the model x axis, the top 0.1 m out along the normal.
    QVERIFY(std::abs((o.loops[0][1] - o.loops[0][0]).norm() - 0.4) < 1e-12);
    QVERIFY(std::abs((o.loops[0][1] - o.loops[0][0]).normalized().dot(Eigen::Vector3d::UnitX())) > 0.999);
    QVERIFY(std::abs((o.loops[1][0] - box.center).dot(box.normal) - 0.1) < 1e-12);
  }

  void placementsFromTheBundle() {
    const auto& demo = LoadDemo();
    const auto available = AvailablePlacements(demo.bundle.get());
    QCOMPARE(available.front(), ModelPlacement::kTruth);
    QVERIFY(std::find(available.begin(), available.end(), ModelPlacement::kGuess) != available.end());
    QCOMPARE(AvailablePlacements(nullptr), std::vector<ModelPlacement>{ModelPlacement::kIdentity});
    const hull::Pose guess = PlacementPose(demo.bundle.get(), ModelPlacement::kGuess);
    const hull::Pose truth = PlacementPose(demo.bundle.get(), ModelPlacement::kTruth);
    // The simulated guess is off by tens of centimetres.
    QVERIFY(hull::Pose::DistanceBetween(guess, truth) > 0.05);
  }

  void pickDetailsDescribeWhatWasPicked() {
    const auto& demo = LoadDemo();
    const PickInfo keyframe = DescribeKeyframe(*demo.bundle, *demo.overlays, 5);
    QCOMPARE(keyframe.kind, PickKind::kKeyframe);
    QCOMPARE(keyframe.title, QStringLiteral("Keyframe %1").arg(demo.bundle->nav[5].keyframe));
    QStringList labels;
    for (const auto& row : keyframe.rows) labels << row.first;
    QVERIFY(labels.contains(QStringLiteral("DVL ranges (m)")));
    QVERIFY(labels.contains(QStringLiteral("Position (truth)")));
    QVERIFY(labels.contains(QStringLiteral("Features observed")));
    const PickInfo object = DescribeObject(*demo.bundle, *demo.overlays, 0, hull::Pose());
    QCOMPARE(object.kind, PickKind::kObject);
    QCOMPARE(object.id, QString::fromStdString(demo.bundle->truth->objects[0].id));
    QCOMPARE(DescribeLandmark(*demo.overlays, -1).kind, PickKind::kNone);
  }

  // --- the demo cache ---

  void demoCacheIsAtomicAndReused() {
    QTemporaryDir root;
    const std::string cache = QFile::encodeName(root.path()).toStdString();
    CancelAtOnce cancel;
    QVERIFY_EXCEPTION_THROWN(PrepareDemo(cache, cancel), hull::Cancelled);
    QVERIFY(QDir(root.path()).entryList(QDir::AllEntries | QDir::NoDotAndDotDot).isEmpty());

    hull::NullProgress progress;
    const DemoFiles first = PrepareDemo(cache, progress);
    QVERIFY(first.simulated);
    QVERIFY(IsValidDemo(first.directory));
    QCOMPARE(QDir(root.path()).entryList(QDir::AllEntries | QDir::NoDotAndDotDot),
             QStringList{QStringLiteral("demo-1")});
    const DemoFiles second = PrepareDemo(cache, progress);
    QVERIFY(!second.simulated);
    QCOMPARE(second.directory, first.directory);

    // A damaged copy is simulated again.
    WriteText(QFile::decodeName(first.directory.c_str()) + QStringLiteral("/nav.csv"), "keyframe,t\n1,oops\n");
    QVERIFY(!IsValidDemo(first.directory));
    QVERIFY(PrepareDemo(cache, progress).simulated);
    QVERIFY(IsValidDemo(first.directory));
  }

  // --- project files ---

  void projectRoundTrip() {
    QTemporaryDir dir;
    ProjectData p;
    p.mesh_path = dir.filePath(QStringLiteral("models/hull.ply"));
    p.bundle_path = dir.filePath(QStringLiteral("surveys/day-1"));
    p.parameters = DefaultValues(DefaultParameterTable());
    p.parameters.insert(QStringLiteral("sigma1"), 0.035);
    p.parameters.insert(QStringLiteral("model"), QStringLiteral("naive"));
    p.parameters.insert(QStringLiteral("dbscan_min_points"), 7);
    ChangeViewAsAUserWould(&p);
    const QString file = dir.filePath(QStringLiteral("inspection.hiproj"));
    WriteProject(file, p);
    const ProjectData q = ReadProject(file, DefaultParameterTable(), CheckDefaultParameters);
    QCOMPARE(q.mesh_path, p.mesh_path);
    QCOMPARE(q.bundle_path, p.bundle_path);
    QCOMPARE(q.parameters, p.parameters);
    QCOMPARE(q.placement, p.placement);
    QVERIFY(q.scene == p.scene);
    QVERIFY(q.camera.has_value());
    QVERIFY(*q.camera == *p.camera);
  }

  void projectInputsAreRelativeToTheProject() {
    QTemporaryDir dir;
    QDir(dir.path()).mkpath(QStringLiteral("job/data"));
    ProjectData p;
    p.mesh_path = dir.filePath(QStringLiteral("job/data/hull.ply"));
    p.bundle_path = dir.filePath(QStringLiteral("job/data/survey"));
    p.parameters = DefaultValues(DefaultParameterTable());
    WriteProject(dir.filePath(QStringLiteral("job/p.hiproj")), p);
    QFile f(dir.filePath(QStringLiteral("job/p.hiproj")));
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QByteArray json = f.readAll();
    QVERIFY2(json.contains("\"mesh\": \"data/hull.ply\""), json.constData());
    QVERIFY2(json.contains("\"survey\": \"data/survey\""), json.constData());
    f.close();
    // The whole folder moves; the project still finds its inputs.
    QVERIFY(QDir(dir.path()).rename(QStringLiteral("job"), QStringLiteral("moved")));
    const ProjectData q =
        ReadProject(dir.filePath(QStringLiteral("moved/p.hiproj")), DefaultParameterTable(), CheckDefaultParameters);
    QCOMPARE(q.mesh_path, dir.filePath(QStringLiteral("moved/data/hull.ply")));
    QCOMPARE(q.bundle_path, dir.filePath(QStringLiteral("moved/data/survey")));
  }

  void malformedProjectsNameFileLineAndColumn() {
    QTemporaryDir dir;
    const QString file = dir.filePath(QStringLiteral("bad.hiproj"));
    auto error_of = [&](const QByteArray& text) -> hull::SourceLocation {
      WriteText(file, text);
      try {
        ReadProject(file, DefaultParameterTable(), CheckDefaultParameters);
      } catch (const hull::InputError& e) {
        return e.where();
      }
      return {};
    };
    hull::SourceLocation w = error_of("{\n  \"format\": \"hullinspect-project\",\n  \"version\": 1,\n  oops\n}\n");
    QCOMPARE(QString::fromStdString(w.file), file);
    QCOMPARE(w.line, 4);
    QVERIFY(w.column > 0);

    w = error_of(
        "{\n  \"format\": \"hullinspect-project\",\n  \"version\": 1,\n  \"parameters\": {\n    \"sigma1\": \"big\"\n  "
        "}\n}\n");
    QCOMPARE(w.field, std::string("parameters.sigma1"));
    QCOMPARE(w.line, 5);

    w = error_of("{\"format\": \"hullinspect-project\", \"version\": 1, \"parameters\": {\"sigma1\": 3.0}}");
    QCOMPARE(w.field, std::string("parameters.sigma1"));  // must stay below sigma0

    w = error_of("{\"format\": \"hullinspect-project\", \"version\": 2}");
    QCOMPARE(w.field, std::string("version"));

    w = error_of("{\"format\": \"something-else\", \"version\": 1}");
    QCOMPARE(w.field, std::string("format"));

    w = error_of(
        "{\"format\": \"hullinspect-project\", \"version\": 1, \"view\": {\"camera\": {\"position\": [1, 2]}}}");
    QCOMPARE(w.field, std::string("view.camera.position"));

    // A placement this version does not know is refused, not silently
    // replaced by the best available one when the project opens.
    w = error_of("{\"format\": \"hullinspect-project\", \"version\": 1,\n \"model_placement\": \"gues\"}");
    QCOMPARE(w.field, std::string("model_placement"));
    QCOMPARE(w.line, 2);
  }

  // The fuzz seeds are what the writer writes today (HI_WRITE_PROJECT_SEEDS=1
  // rewrites them after a format change), and each reads back to its data.
  void projectFuzzSeedsAreWhatTheGuiWrites() {
    const QString corpus = QStringLiteral(HI_SOURCE_DIR "/tests/fuzz/corpus/project/");
    const QString dir = QStringLiteral("/data/job-17");
    const bool rewrite = qEnvironmentVariableIsSet("HI_WRITE_PROJECT_SEEDS");
    QTemporaryDir tmp;
    for (const auto& [name, p] : ProjectSeeds(dir)) {
      const QByteArray json = ProjectToJson(p, dir);
      if (rewrite) WriteText(corpus + name, json);
      QVERIFY2(ReadText(corpus + name) == json, qPrintable(name + QStringLiteral(" differs from ProjectToJson")));
      // Read from a folder of its own: the inputs resolve against it.
      const QString file = tmp.filePath(name);
      WriteText(file, json);
      const ProjectData q = ReadProject(file, DefaultParameterTable(), CheckDefaultParameters);
      auto moved = [&](const QString& path) {
        return path.isEmpty() ? path
                              : QDir::cleanPath(tmp.path() + QLatin1Char('/') + QDir(dir).relativeFilePath(path));
      };
      QCOMPARE(q.mesh_path, moved(p.mesh_path));
      QCOMPARE(q.bundle_path, moved(p.bundle_path));
      QCOMPARE(q.parameters, p.parameters);
      QCOMPARE(q.placement, p.placement);
      QVERIFY(q.scene == p.scene);
      QCOMPARE(q.camera.has_value(), p.camera.has_value());
    }
  }

  // Inputs the fuzz harness found (tests/fuzz/regressions/project): refused
  // with the file, line and column, never read.
  void projectFuzzRegressions() {
    const QString dir = QStringLiteral(HI_SOURCE_DIR "/tests/fuzz/regressions/project/");
    // Qt 5.15's parser leaked the first value of a duplicate key when it is
    // an array or object (and kept the second silently).
    const QString duplicate = dir + QStringLiteral("duplicate-array-key.hiproj");
    try {
      ReadProject(duplicate, DefaultParameterTable(), CheckDefaultParameters);
      QFAIL("a project with a duplicate key was read");
    } catch (const hull::InputError& e) {
      QCOMPARE(QString::fromStdString(e.where().file), duplicate);
      QCOMPARE(e.where().line, 9);
      QVERIFY(e.where().column > 0);
      QVERIFY2(std::string(e.what()).find("duplicate key \"view_up\"") != std::string::npos, e.what());
    }
  }

  // JSON that Qt's parser accepts but JSON does not is refused like any
  // other malformed file (the same strict parser as survey.json).
  void projectsAreStrictJson() {
    QTemporaryDir dir;
    const QString file = dir.filePath(QStringLiteral("p.hiproj"));
    auto refused_at_line = [&](const QByteArray& text) {
      WriteText(file, text);
      try {
        ReadProject(file, DefaultParameterTable(), CheckDefaultParameters);
      } catch (const hull::InputError& e) {
        return QString::fromStdString(e.where().file) == file ? e.where().line : -1;
      }
      return 0;
    };
    QCOMPARE(refused_at_line(
                 "{\"format\": \"hullinspect-project\",\n \"version\": 1,\n \"view\": {\"frustum_stride\": .5}}"),
             3);
    QCOMPARE(refused_at_line("{\"format\": \"hullinspect-project\", \"version\": 1,\n\"inputs\": {},\n\"inputs\": {}}"),
             3);
    QCOMPARE(refused_at_line("{\"format\": \"hullinspect-project\", \"version\": 1}"), 0);
  }

  void savingReplacesTheFileWhole() {
    QTemporaryDir dir;
    const QString file = dir.filePath(QStringLiteral("p.hiproj"));
    WriteText(file, QByteArray(100000, 'x'));
    ProjectData p;
    p.parameters = DefaultValues(DefaultParameterTable());
    WriteProject(file, p);
    const ProjectData q = ReadProject(file, DefaultParameterTable(), CheckDefaultParameters);
    QCOMPARE(q.parameters, p.parameters);
    QVERIFY_EXCEPTION_THROWN(WriteProject(dir.filePath(QStringLiteral("no/such/folder/p.hiproj")), p),
                             std::runtime_error);
  }

  // --- command line and opened paths ---

  // The front end's DVL height check of mono tracks from the parameter
  // panel: on by default with the struct's bounds, off and moved bounds
  // reach FrontEndOptions and the front end's cache key, a bound of the
  // wrong sign is an error naming its parameter.
  void trackCheckParametersReachTheFrontEnd() {
    ParameterValues values = DefaultValues(DefaultParameterTable());
    const hull::FrontEndOptions defaults = FrontEndOptionsFrom(values);
    QVERIFY(defaults.tracks.check_dvl_height);
    QCOMPARE(defaults.tracks.check_max_height, hull::TrackOptions().check_max_height);
    QCOMPARE(defaults.tracks.check_min_height, hull::TrackOptions().check_min_height);
    const QString key = FrontEndKey(values);
    values.insert(QStringLiteral("fe_track_check"), QStringLiteral("off"));
    values.insert(QStringLiteral("fe_track_check_max_height"), 0.4);
    values.insert(QStringLiteral("fe_track_check_min_height"), -0.2);
    const hull::FrontEndOptions changed = FrontEndOptionsFrom(values);
    QVERIFY(!changed.tracks.check_dvl_height);
    QCOMPARE(changed.tracks.check_max_height, 0.4);
    QCOMPARE(changed.tracks.check_min_height, -0.2);
    QVERIFY(FrontEndKey(values) != key);
    values.insert(QStringLiteral("fe_track_check_max_height"), -0.1);
    const std::vector<ParameterError> errors = CheckDefaultParameters(values);
    QVERIFY(std::any_of(errors.begin(), errors.end(),
                        [](const ParameterError& e) { return e.key == QLatin1String("fe_track_check_max_height"); }));
  }

  void refinementParametersReachTheFrontEnd() {
    ParameterValues values = DefaultValues(DefaultParameterTable());
    const hull::FrontEndOptions defaults = FrontEndOptionsFrom(values);
    QVERIFY(defaults.tracks.refine);
    QCOMPARE(defaults.tracks.refine_max_shift, hull::TrackOptions().refine_max_shift);
    QCOMPARE(defaults.tracks.refine_min_ncc, hull::TrackOptions().refine_min_ncc);
    const QString key = FrontEndKey(values);
    values.insert(QStringLiteral("fe_refine"), QStringLiteral("off"));
    values.insert(QStringLiteral("fe_refine_max_shift"), 1.5);
    values.insert(QStringLiteral("fe_refine_min_ncc"), 0.6);
    const hull::FrontEndOptions changed = FrontEndOptionsFrom(values);
    QVERIFY(!changed.tracks.refine);
    QCOMPARE(changed.tracks.refine_max_shift, 1.5);
    QCOMPARE(changed.tracks.refine_min_ncc, 0.6);
    QVERIFY(FrontEndKey(values) != key);
    values.insert(QStringLiteral("fe_refine_min_ncc"), 1.5);
    const std::vector<ParameterError> errors = CheckDefaultParameters(values);
    QVERIFY(std::any_of(errors.begin(), errors.end(),
                        [](const ParameterError& e) { return e.key == QLatin1String("fe_refine_min_ncc"); }));
  }

  // The peak fit from the parameter panel: off by default (MappingOptions'),
  // "on" reaches MappingOptions.
  void peakFitParameterReachesTheMapping() {
    ParameterValues values = DefaultValues(DefaultParameterTable());
    QCOMPARE(MappingOptionsFrom(values).peak_fit, hull::MappingOptions().peak_fit);
    values.insert(QStringLiteral("peak_fit"), QStringLiteral("on"));
    QVERIFY(MappingOptionsFrom(values).peak_fit);
    values.insert(QStringLiteral("peak_fit"), QStringLiteral("off"));
    QVERIFY(!MappingOptionsFrom(values).peak_fit);
  }

  // The E-step's rule and the seeds across views from the parameter panel:
  // the defaults are the core's, the other choice reaches the options and
  // changes the stage's key (so the stage is run again).
  void labelsAndSeedsParametersReachTheCore() {
    ParameterValues values = DefaultValues(DefaultParameterTable());
    QVERIFY(AdjustmentOptionsFrom(values).labels == hull::AdjustmentOptions().labels);
    QCOMPARE(MappingOptionsFrom(values).shape_seed_across_views, hull::MappingOptions().shape_seed_across_views);
    const QString adjust_key = AdjustmentKey(values), map_key = MappingKey(values);
    values.insert(QStringLiteral("labels"), QStringLiteral("estimate"));
    QVERIFY(AdjustmentOptionsFrom(values).labels == hull::LabelRule::kEstimate);
    QVERIFY(AdjustmentKey(values) != adjust_key);
    values.insert(QStringLiteral("labels"), QStringLiteral("cavity"));
    QVERIFY(AdjustmentOptionsFrom(values).labels == hull::LabelRule::kCavity);
    values.insert(QStringLiteral("shape_seed_across_views"), QStringLiteral("off"));
    QVERIFY(!MappingOptionsFrom(values).shape_seed_across_views);
    QVERIFY(MappingKey(values) != map_key);
    values.insert(QStringLiteral("shape_seed_across_views"), QStringLiteral("on"));
    QVERIFY(MappingOptionsFrom(values).shape_seed_across_views);
  }

  void anotherSurveyClearsTheLayersOfThePrevious() {
    // A comparison and a photomosaic on screen belong to the inputs open:
    // opening another mesh or survey (or new features) drops them, as it
    // drops the adjustment and the mapping (issue 25.5).
    for (int input = 0; input < 2; ++input) {
      Session session;
      session.SetComparison(std::make_shared<hull::SurveyComparisonRun>());
      session.SetMosaic(std::make_shared<MosaicLayer>());
      QSignalSpy comparison(&session, &Session::comparisonChanged), mosaic(&session, &Session::mosaicChanged);
      if (input == 0) {
        session.SetMesh(LoadedMesh{QStringLiteral("hull.ply"), std::make_shared<hull::TriangleMesh>()});
      } else {
        session.SetSurvey(LoadedSurvey{QStringLiteral("survey"), std::make_shared<hull::SurveyBundle>(),
                                       std::make_shared<SurveyOverlays>()});
      }
      QVERIFY(!session.comparison());
      QVERIFY(!session.mosaic());
      QCOMPARE(comparison.count(), 1);
      QCOMPARE(mosaic.count(), 1);
    }
  }

  void scaleBarsAreRoundAndSized() {
    // 480 px spanning 10 m: 150 px is 3.1 m; 2 m (96 px) is nearer on a log
    // scale than 5 m (240 px).
    ScaleBar bar = ChooseScaleBar(10.0, 480);
    QCOMPARE(bar.metres, 2.0);
    QCOMPARE(bar.pixels, 96.0);
    QCOMPARE(QString::fromStdString(bar.label), QStringLiteral("2 m"));
    bar = ChooseScaleBar(0.4, 600);  // 150 px is 0.1 m
    QVERIFY(std::abs(bar.metres - 0.1) < 1e-12);
    QCOMPARE(QString::fromStdString(bar.label), QStringLiteral("0.1 m"));
    bar = ChooseScaleBar(0.03, 400);  // 150 px is 1.125 cm: 1 cm
    QCOMPARE(QString::fromStdString(bar.label), QStringLiteral("0.01 m"));
    for (double span : {0.013, 0.7, 3.3, 47.0, 1234.0}) {
      const ScaleBar b = ChooseScaleBar(span, 700);
      QVERIFY2(b.pixels >= 94 && b.pixels <= 238, qPrintable(QString::number(b.pixels)));
    }
    QCOMPARE(ChooseScaleBar(0.0, 480).metres, 0.0);
    QCOMPARE(ChooseScaleBar(5.0, 0).metres, 0.0);
    QCOMPARE(ChooseScaleBar(std::nan(""), 480).metres, 0.0);
  }

  void deviationHistogramsCountEveryValueOnce() {
    const std::vector<double> values = {-0.2, -0.05, -0.01, 0.0, 0.0, 0.02, 0.049, 0.05, 0.11, std::nan("")};
    const DeviationHistogram h = ComputeDeviationHistogram(values, -0.05, 0.05, 4, 0.02);
    QCOMPARE(h.total, 9);
    QCOMPARE(h.below, 1);                                // -0.2
    QCOMPARE(h.above, 1);                                // 0.11
    QCOMPARE(h.counts, (std::vector<int>{1, 1, 3, 2}));  // 0.05 (= hi) in the last bin
    QCOMPARE(h.within, 4);                               // -0.01, 0, 0, 0.02
    QCOMPARE(h.max_count(), 3);
    QVERIFY(std::abs(h.WithinFraction() - 4.0 / 9.0) < 1e-12);
    QVERIFY(ComputeDeviationHistogram(values, 0.1, 0.1, 4, 0).counts.empty());
    QCOMPARE(ComputeDeviationHistogram(values, -1, 1, 4, 0).within, 0);
  }

  void commandLine() {
    LaunchOptions o = ParseCommandLine({QStringLiteral("--demo")});
    QVERIFY(o.demo && o.error.isEmpty() && o.paths.isEmpty());
    o = ParseCommandLine({QStringLiteral("hull.ply"), QStringLiteral("survey"), QStringLiteral("p.hiproj")});
    QCOMPARE(o.paths.size(), 3);
    QVERIFY(ParseCommandLine({QStringLiteral("--frobnicate")}).error.contains(QStringLiteral("--frobnicate")));
    QVERIFY(!ParseCommandLine({QStringLiteral("--demo"), QStringLiteral("hull.ply")}).error.isEmpty());
    o = ParseCommandLine({QStringLiteral("--"), QStringLiteral("--odd-name.ply")});
    QCOMPARE(o.paths, QStringList{QStringLiteral("--odd-name.ply")});
    QVERIFY(ParseCommandLine({QStringLiteral("--help")}).help);
    QVERIFY(ParseCommandLine({QStringLiteral("--version")}).version);
    QVERIFY(HeadlessText().contains(QStringLiteral("hullinspect-cli run --demo --out DIR")));
  }

  void openedPathsAreSorted() {
    const auto& demo = LoadDemo();
    ClassifiedPaths c = ClassifyPaths({demo.mesh_path, demo.directory});
    QVERIFY(c.error.isEmpty());
    QCOMPARE(QDir::cleanPath(c.mesh), QDir::cleanPath(demo.mesh_path));
    QCOMPARE(QDir::cleanPath(c.bundle), QDir::cleanPath(demo.directory));
    c = ClassifyPaths({demo.directory + QStringLiteral("/survey.json")});
    QCOMPARE(QDir::cleanPath(c.bundle), QDir::cleanPath(demo.directory));

    QTemporaryDir dir;
    const QString text = dir.filePath(QStringLiteral("notes.txt"));
    WriteText(text, "hello");
    QVERIFY(ClassifyPaths({text}).error.contains(QStringLiteral("not a mesh")));
    QVERIFY(ClassifyPaths({dir.filePath(QStringLiteral("missing.ply"))}).error.contains(QStringLiteral("no such")));
    QVERIFY(ClassifyPaths({demo.mesh_path, demo.mesh_path}).error.contains(QStringLiteral("one mesh")));
    const QString project = dir.filePath(QStringLiteral("p.hiproj"));
    WriteText(project, "{}");
    QVERIFY(!ClassifyPaths({project, demo.mesh_path}).error.isEmpty());
    QCOMPARE(ClassifyPaths({project}).project, project);
  }
};

HI_GUI_TEST_MAIN(UiLogicTest)
#include "ui_logic_test.moc"
