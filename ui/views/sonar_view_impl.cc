#include "ui/views/sonar_view_impl.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <cmath>

#include "sonar/acoustic_camera.h"
#include "ui/views/scene_guides_impl.h"
#include "ui/views/scene_polydata_impl.h"
#include "ui/views/vtk_grab_impl.h"

namespace hull::ui {

namespace {

vtkSmartPointer<vtkPolyData> Points(const std::vector<Eigen::Vector3d>& points) {
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> p;
  vtkNew<vtkCellArray> verts;
  for (const auto& q : points) {
    const vtkIdType id = p->InsertNextPoint(q.data());
    verts->InsertNextCell(1, &id);
  }
  poly->SetPoints(p);
  poly->SetVerts(verts);
  return poly;
}

vtkSmartPointer<vtkPolyData> Polyline(const std::vector<Eigen::Vector3d>& points) {
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> p;
  vtkNew<vtkCellArray> lines;
  for (const auto& q : points) p->InsertNextPoint(q.data());
  if (points.size() >= 2) {
    lines->InsertNextCell(static_cast<vtkIdType>(points.size()));
    for (std::size_t i = 0; i < points.size(); ++i) lines->InsertCellPoint(static_cast<vtkIdType>(i));
  }
  poly->SetPoints(p);
  poly->SetLines(lines);
  return poly;
}

// Unit spheres (12 x 7) placed and stretched as the ellipsoids.
vtkSmartPointer<vtkPolyData> Ellipsoids(const std::vector<Ellipsoid>& ellipsoids, double scale) {
  constexpr int kAround = 12, kUp = 7;
  std::vector<Eigen::Vector3d> unit;
  for (int j = 0; j <= kUp; ++j) {
    const double theta = M_PI * j / kUp;
    for (int i = 0; i < kAround; ++i) {
      const double phi = 2 * M_PI * i / kAround;
      unit.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    }
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> p;
  vtkNew<vtkCellArray> quads;
  for (const Ellipsoid& e : ellipsoids) {
    const vtkIdType base = p->GetNumberOfPoints();
    const Eigen::Matrix3d A = e.axes * (scale * e.radii.cwiseMax(1e-5)).asDiagonal();
    for (const auto& u : unit) {
      const Eigen::Vector3d q = e.centre + A * u;
      p->InsertNextPoint(q.data());
    }
    for (int j = 0; j < kUp; ++j) {
      for (int i = 0; i < kAround; ++i) {
        const vtkIdType ids[4] = {base + j * kAround + i, base + j * kAround + (i + 1) % kAround,
                                  base + (j + 1) * kAround + (i + 1) % kAround, base + (j + 1) * kAround + i};
        quads->InsertNextCell(4, ids);
      }
    }
  }
  poly->SetPoints(p);
  poly->SetPolys(quads);
  return poly;
}

// The sonar's field of view from a pose: four rays to the far corners at
// range_max and the far rectangle.
vtkSmartPointer<vtkPolyData> FieldOfView(const Vector6d& pose, const SonarSensor& sensor) {
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> p;
  vtkNew<vtkCellArray> lines;
  const Eigen::Vector3d origin = pose.head<3>();
  const vtkIdType o = p->InsertNextPoint(origin.data());
  vtkIdType corners[4];
  const double az[4] = {-0.5, 0.5, 0.5, -0.5}, el[4] = {-0.5, -0.5, 0.5, 0.5};
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d q =
        SonarBackProject<double>(pose, sensor.range_max, az[k] * sensor.azimuth_fov, el[k] * sensor.elevation_fov);
    corners[k] = p->InsertNextPoint(q.data());
    const vtkIdType ray[2] = {o, corners[k]};
    lines->InsertNextCell(2, ray);
  }
  const vtkIdType rect[5] = {corners[0], corners[1], corners[2], corners[3], corners[0]};
  lines->InsertNextCell(5, rect);
  poly->SetPoints(p);
  poly->SetLines(lines);
  return poly;
}

}  // namespace

SonarViewImpl::SonarViewImpl() {
  window_ = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  window_->SetMultiSamples(0);  // as the 3-D scene: cheap frames with a software OpenGL
  renderer_ = vtkSmartPointer<vtkRenderer>::New();
  renderer_->GradientBackgroundOn();
  renderer_->SetBackground(0.05, 0.06, 0.09);
  renderer_->SetBackground2(0.22, 0.25, 0.30);
  window_->AddRenderer(renderer_);
  guides_ = std::make_unique<SceneGuides>(window_, renderer_);
  const double colours[kLayers][3] = {{0.2, 0.85, 0.3}, {0.3, 0.5, 1.0},    {1.0, 0.25, 0.2}, {1.0, 0.35, 0.3},
                                      {0.2, 0.85, 0.3}, {0.65, 0.65, 0.65}, {1.0, 0.3, 0.25}, {1.0, 0.65, 0.2},
                                      {0.8, 0.85, 0.9}, {0.55, 0.58, 0.62}};
  for (int layer = 0; layer < kLayers; ++layer) {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(vtkSmartPointer<vtkPolyData>::New());
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    vtkProperty* p = actor->GetProperty();
    p->SetColor(colours[layer][0], colours[layer][1], colours[layer][2]);
    p->LightingOff();
    switch (layer) {
      case kTrueFeatures:
        p->SetPointSize(14);
        p->RenderPointsAsSpheresOn();
        break;
      case kInitial:
      case kEstimated:
        p->SetPointSize(9);
        p->RenderPointsAsSpheresOn();
        break;
      case kFeatureEllipsoids:
      case kPoseEllipsoids:
        p->SetOpacity(0.28);
        p->LightingOn();
        break;
      case kFieldOfView:
        p->SetOpacity(0.6);
        p->SetLineWidth(1.0);
        break;
      case kScene:
        p->SetOpacity(0.35);
        p->LightingOn();
        p->SetRepresentationToSurface();
        break;
      default:
        p->SetLineWidth(2.5);
        break;
    }
    renderer_->AddActor(actor);
    actors_.push_back(actor);
  }
}

SonarViewImpl::~SonarViewImpl() = default;

void SonarViewImpl::SetRun(std::shared_ptr<const SonarRun> run) {
  run_ = std::move(run);
  step_ = run_ ? run_->steps() - 1 : 0;
  Rebuild();
}

void SonarViewImpl::SetStep(int step) {
  step_ = step;
  Rebuild();
}

void SonarViewImpl::SetEllipsoidScale(double scale) {
  scale_ = scale;
  Rebuild();
}

void SonarViewImpl::SetSmoother(bool smoother) {
  smoother_ = smoother;
  Rebuild();
}

void SonarViewImpl::SetSceneVisible(bool visible) {
  scene_visible_ = visible;
  Rebuild();
}

void SonarViewImpl::Rebuild() {
  std::vector<vtkSmartPointer<vtkPolyData>> data(kLayers);
  for (auto& d : data) d = vtkSmartPointer<vtkPolyData>::New();
  true_features = initial = estimated = feature_ellipsoids = pose_ellipsoids = scene_triangles = 0;
  showing_smoother = false;
  if (run_ && run_->scene && scene_visible_) {
    data[kScene] = MeshPolyData(*run_->scene);
    scene_triangles = static_cast<int>(run_->scene->faces.size());
  }
  if (run_ && run_->steps() > 0) {
    step_ = std::clamp(step_, 0, run_->steps() - 1);
    const SonarStepRecord& now = run_->result.steps[step_];
    const auto& truth = run_->sequence->truth;
    if (truth) {
      data[kTrueFeatures] = Points(truth->features);
      true_features = static_cast<int>(truth->features.size());
      std::vector<Eigen::Vector3d> path;
      for (int i = 0; i <= step_ && i < static_cast<int>(truth->poses.size()); ++i)
        path.push_back(truth->poses[i].head<3>());
      data[kTrueTrajectory] = Polyline(path);
    }
    showing_smoother = smoother_ && run_->smoother.has_value();
    std::vector<Eigen::Vector3d> est;
    std::vector<Ellipsoid> ell;
    std::vector<Eigen::Vector3d> path, dead;
    std::vector<Ellipsoid> poses;
    for (int i = 0; i <= step_; ++i) dead.push_back(run_->result.steps[i].dead_reckoning.head<3>());
    if (showing_smoother) {
      // The smoother's: its final points (every one, smoothed or held out at
      // the EKF's) and its poses up to the step, each with its covariance.
      const SonarSmootherResult& sm = run_->smoother->result;
      for (const SonarSmoothedFeature& f : sm.features) {
        est.push_back(f.position);
        if (f.covariance.allFinite()) ell.push_back(ThreeSigmaEllipsoid(f.position, f.covariance));
      }
      for (int i = 0; i <= step_ && i < static_cast<int>(sm.poses.size()); ++i) {
        path.push_back(sm.poses[i].head<3>());
        const Eigen::Matrix3d c = sm.pose_covariances[i].topLeftCorner<3, 3>();
        if (c.allFinite()) poses.push_back(ThreeSigmaEllipsoid(sm.poses[i].head<3>(), c));
      }
    } else {
      std::vector<Eigen::Vector3d> first;
      for (std::size_t i = 0; i < run_->initial.size(); ++i) {
        if (run_->first_step[i] <= now.estimate.step) first.push_back(run_->initial[i]);
      }
      data[kInitial] = Points(first);
      initial = static_cast<int>(first.size());
      for (const SonarFeatureEstimate& f : now.features) {
        est.push_back(f.position);
        ell.push_back(ThreeSigmaEllipsoid(f.position, f.covariance));
      }
      for (int i = 0; i <= step_; ++i) {
        const SonarStepRecord& r = run_->result.steps[i];
        path.push_back(r.estimate.pose.head<3>());
        poses.push_back(
            ThreeSigmaEllipsoid(r.estimate.pose.head<3>(), r.estimate.pose_covariance.topLeftCorner<3, 3>()));
      }
    }
    data[kEstimated] = Points(est);
    data[kFeatureEllipsoids] = Ellipsoids(ell, scale_);
    estimated = static_cast<int>(est.size());
    feature_ellipsoids = static_cast<int>(ell.size());
    data[kTrajectory] = Polyline(path);
    data[kDeadReckoning] = Polyline(dead);
    data[kPoseEllipsoids] = Ellipsoids(poses, scale_);
    pose_ellipsoids = static_cast<int>(poses.size());
    data[kFieldOfView] = FieldOfView(now.estimate.pose, run_->sequence->sensor);
  }
  for (int layer = 0; layer < kLayers; ++layer) {
    vtkPolyDataMapper::SafeDownCast(actors_[layer]->GetMapper())->SetInputData(data[layer]);
  }
}

void SonarViewImpl::ResetCamera(bool whole_run) {
  if (!run_ || run_->bounds.isEmpty()) return;
  Eigen::AlignedBox3d b = run_->bounds;
  if (!whole_run) {
    Eigen::AlignedBox3d features;
    for (const auto& p : run_->initial) features.extend(p);
    if (run_->sequence->truth) {
      for (const auto& p : run_->sequence->truth->features) features.extend(p);
    }
    if (!features.isEmpty()) {
      const Eigen::Vector3d pad = Eigen::Vector3d::Constant(0.15 * features.sizes().maxCoeff() + 0.05);
      b = Eigen::AlignedBox3d(features.min() - pad, features.max() + pad);
    }
  }
  const Eigen::Vector3d c = b.center();
  vtkCamera* camera = renderer_->GetActiveCamera();
  // From above and behind the start, z down: "up" on screen is -z.
  camera->SetFocalPoint(c.data());
  const Eigen::Vector3d from = c + Eigen::Vector3d(-1.0, -1.4, -1.2);
  camera->SetPosition(from.data());
  camera->SetViewUp(0, 0, -1);
  double bounds[6] = {b.min().x(), b.max().x(), b.min().y(), b.max().y(), b.min().z(), b.max().z()};
  renderer_->ResetCamera(bounds);
  camera->Dolly(1.2);
  renderer_->ResetCameraClippingRange();
}

void SonarViewImpl::Render() {
  renderer_->ResetCameraClippingRange();
  window_->Render();
}

QImage SonarViewImpl::Grab() {
  if (!window_->GetReadyForRendering()) return {};
  Render();
  return GrabRenderWindow(window_);
}

}  // namespace hull::ui
