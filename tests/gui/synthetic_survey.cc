#include "synthetic_survey.h"

#include <QDir>
#include <QFile>
#include <cmath>

#include "geometry/mesh_io.h"
#include "support/test_meshes.h"
#include "survey/survey_io.h"
#include "ui/session/survey_overlays.h"

namespace hull::ui::testing {

namespace {

const Pose kModelPose = Pose::FromXyzRpy(0, 0, 5, M_PI, 0, 0.3);

// A landmark in M with its truth.
void AddLandmark(SurveyTruth& truth, std::int64_t* next_id, const Eigen::Vector3d& p_M, double deviation,
                 const std::string& object) {
  TrueLandmark l;
  l.landmark = (*next_id)++;
  l.p = kModelPose * p_M;
  l.deviation = deviation;
  l.object = object;
  truth.landmarks.push_back(l);
}

TrueObject Object(const std::string& id, ObjectKind kind, const Eigen::Vector3d& c, double radius, double height,
                  const Eigen::Vector3d& size = Eigen::Vector3d::Zero()) {
  TrueObject o;
  o.id = id;
  o.kind = kind;
  o.center = c;
  o.normal = -Eigen::Vector3d::UnitZ();  // the bottom's outward normal in M
  o.radius = radius;
  o.height = kind == ObjectKind::kBox ? size.z() : height;
  o.size = size;
  return o;
}

SyntheticSurvey Make() {
  auto mesh = std::make_shared<TriangleMesh>(hull::test::Subdivide(hull::test::Subdivide(
      hull::test::Subdivide(hull::test::MakeBox(Eigen::Vector3d(-10, -3, 0), Eigen::Vector3d(10, 3, 4))))));
  mesh->ComputeNormals();

  auto b = std::make_shared<SurveyBundle>();
  b->manifest.name = "Synthetic test survey";
  b->manifest.vehicle = "HAUV";
  b->manifest.model_hint = "hull.ply";
  b->manifest.model_pose_guess = (Vector6d() << 0.2, -0.1, 5.05, M_PI, 0, 0.32).finished();
  SurveyTruth truth;
  truth.x_gM = kModelPose.ToVector();
  truth.x_s_cT = b->manifest.camera.servo_to_top;

  // Three tracks 1.6 m below the bottom, looking up; the initial navigation drifts.
  const double servo = M_PI / 2;
  std::int64_t keyframe = 0;
  for (int track = 0; track < 3; ++track) {
    const double y = -1.5 + 1.5 * track;
    for (int i = 0; i <= 20; ++i) {
      const double x = track % 2 == 0 ? -6.0 + 0.6 * i : 6.0 - 0.6 * i;
      const double heading = 0.3 + (track % 2 == 0 ? 0.0 : M_PI);
      // Vehicle frame: x forward, z down; in g the bottom is at depth 5.
      const Eigen::Vector3d p_g = kModelPose * Eigen::Vector3d(x, y, -1.6);
      const Pose x_gv_true(Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix(), p_g);
      const double k = static_cast<double>(keyframe);
      const Pose x_gv_nav(
          x_gv_true.quaternion() * Eigen::Quaterniond(Eigen::AngleAxisd(0.001 * k, Eigen::Vector3d::UnitZ())),
          p_g + Eigen::Vector3d(0.004 * k, 0.003 * k, 0.001 * k));
      NavRecord nav;
      nav.keyframe = keyframe;
      nav.t = 1.5 * k;
      nav.x_gv = x_gv_nav.ToVector();
      nav.depth = p_g.z();
      nav.servo = servo;
      b->nav.push_back(nav);
      truth.poses.push_back({keyframe, x_gv_true.ToVector(), servo});

      // DVL: exact ranges to the bottom plane (depth 5 in g).
      DvlRecord d;
      d.keyframe = keyframe;
      const Pose x_gd = DvlPose(b->manifest, x_gv_true.ToVector(), servo);
      for (int beam = 0; beam < 4; ++beam) {
        const Eigen::Vector3d dir = x_gd.Rotate(b->manifest.BeamDirection(beam));
        d.range[beam] = (5.0 - x_gd.translation().z()) / dir.z();
      }
      b->dvl.push_back(d);
      ++keyframe;
    }
  }
  for (std::size_t i = 1; i < b->nav.size(); ++i) {
    OdometryRecord o;
    o.from = b->nav[i - 1].keyframe;
    o.to = b->nav[i].keyframe;
    o.z = (Pose::FromVector(b->nav[i - 1].x_gv).Inverse() * Pose::FromVector(b->nav[i].x_gv)).ToVector();
    b->odometry.push_back(o);
  }

  // Landmarks: a grid on the bottom, denser on the objects, a shallow dent.
  std::int64_t id = 0;
  for (double x = -6.75; x <= 6.75; x += 0.5) {
    for (double y = -2.2; y <= 2.21; y += 0.4) AddLandmark(truth, &id, Eigen::Vector3d(x, y, 0), 0.0, "");
  }
  truth.objects.push_back(Object("cyl-1", ObjectKind::kCylinder, Eigen::Vector3d(2.0, 0.75, 0), 0.3, 0.15));
  truth.objects.push_back(
      Object("box-1", ObjectKind::kBox, Eigen::Vector3d(-3.0, -1.0, 0), 0, 0, Eigen::Vector3d(0.8, 0.4, 0.1)));
  truth.objects.push_back(Object("patch-1", ObjectKind::kPatch, Eigen::Vector3d(4.5, -1.5, 0), 0.25, 0.06));
  for (int i = 0; i < 24; ++i) {
    const double a = 2 * M_PI * i / 24, r = 0.1 + 0.18 * (i % 2);
    AddLandmark(truth, &id, Eigen::Vector3d(2.0 + r * std::cos(a), 0.75 + r * std::sin(a), -0.15), 0.15, "cyl-1");
    AddLandmark(truth, &id, Eigen::Vector3d(-3.0 + 0.35 * std::cos(a), -1.0 + 0.15 * std::sin(a), -0.1), 0.1, "box-1");
    const double h = 0.06 * (1.0 - r * r / 0.09);
    AddLandmark(truth, &id, Eigen::Vector3d(4.5 + 0.7 * r * std::cos(a), -1.5 + 0.7 * r * std::sin(a), -h), h,
                "patch-1");
    AddLandmark(truth, &id, Eigen::Vector3d(-5.0 + 1.5 * r * std::cos(a), 1.5 + 1.5 * r * std::sin(a), 0.05), -0.05,
                "");
  }

  // Feature observations: every landmark each true camera sees.
  SurveyManifest manifest = b->manifest;
  for (const TruePose& pose : truth.poses) {
    const Pose x_gc = CameraPose(manifest, pose.x_gv, pose.servo);
    const Pose x_gcb = x_gc * Pose::FromVector(manifest.camera.top_to_bottom);
    for (const TrueLandmark& l : truth.landmarks) {
      const Eigen::Vector3d top = x_gc.Inverse() * l.p;
      const Eigen::Vector3d bottom = x_gcb.Inverse() * l.p;
      if (top.z() <= 0.1 || bottom.z() <= 0.1) continue;
      FeatureObservation f;
      f.keyframe = pose.keyframe;
      f.landmark = l.landmark;
      f.top = manifest.camera.top.Project(top);
      f.bottom = manifest.camera.bottom.Project(bottom);
      f.has_bottom = true;
      if (!manifest.camera.InImage(f.top) || !manifest.camera.InImage(f.bottom)) continue;
      b->features.push_back(f);
    }
  }
  b->truth = truth;
  return {mesh, b};
}

}  // namespace

const SyntheticSurvey& MakeSyntheticSurvey() {
  static const SyntheticSurvey survey = Make();
  return survey;
}

QString WriteSyntheticSurvey(const QString& directory) {
  const SyntheticSurvey& s = MakeSyntheticSurvey();
  QDir().mkpath(directory);
  const std::string dir = QFile::encodeName(directory).toStdString();
  WriteSurveyBundle(*s.bundle, dir);
  SaveMesh(*s.mesh, dir + "/hull.ply");
  return directory;
}

}  // namespace hull::ui::testing
