// The VTK side of SonarView: one actor per layer, rebuilt at every step.
// Only sonar_view.cc includes this.
#pragma once

#include <vtkSmartPointer.h>

#include <QImage>
#include <memory>
#include <vector>

#include "ui/session/sonar_results.h"

class vtkActor;
class vtkGenericOpenGLRenderWindow;
class vtkRenderer;

namespace hull::ui {

class SceneGuides;

class SonarViewImpl {
 public:
  SonarViewImpl();
  ~SonarViewImpl();

  vtkGenericOpenGLRenderWindow* window() const { return window_; }
  void SetRun(std::shared_ptr<const SonarRun> run);
  void SetStep(int step);
  int step() const { return step_; }
  void SetEllipsoidScale(double scale);
  // The filter's estimates at the step, or the smoother's (when the run has them).
  void SetSmoother(bool smoother);
  void SetSceneVisible(bool visible);
  void ResetCamera(bool whole_run);
  void Render();
  QImage Grab();

  int true_features = 0, initial = 0, estimated = 0, feature_ellipsoids = 0, pose_ellipsoids = 0;
  int scene_triangles = 0;
  bool showing_smoother = false;

 private:
  enum Layer {
    kTrueFeatures,
    kInitial,
    kEstimated,
    kFeatureEllipsoids,
    kTrueTrajectory,
    kDeadReckoning,
    kTrajectory,
    kPoseEllipsoids,
    kFieldOfView,
    kScene,
    kLayers
  };
  void Rebuild();

  vtkSmartPointer<vtkGenericOpenGLRenderWindow> window_;
  vtkSmartPointer<vtkRenderer> renderer_;
  std::vector<vtkSmartPointer<vtkActor>> actors_;
  std::unique_ptr<SceneGuides> guides_;  // orientation axes (the world's x, y, z) and scale bar
  std::shared_ptr<const SonarRun> run_;
  int step_ = 0;
  double scale_ = 1.0;
  bool smoother_ = false;
  bool scene_visible_ = true;
};

}  // namespace hull::ui
