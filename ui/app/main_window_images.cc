// The main window's images view and feature extraction: the "Images" dock
// (views/images_view.h) fed from the Session's survey, front-end result and
// adjustment, the FrontEndController driven by the parameter panel, and the
// Inspection menu's "Extract features".
#include <QAction>
#include <QDockWidget>
#include <QMenu>
#include <QStatusBar>

#include "ui/app/main_window.h"
#include "ui/controllers/front_end_controller.h"
#include "ui/jobs/job_runner.h"
#include "ui/panels/parameter_panel.h"
#include "ui/panels/survey_summary_panel.h"
#include "ui/session/session.h"
#include "ui/views/images_view.h"
#include "ui/views/keyframe_view.h"
#include "ui/views/scene_view.h"

namespace hull::ui {

void MainWindow::CreateImagesDock() {
  images_ = new ImagesView(this);
  images_dock_ = AddView(images_, QStringLiteral("Images"), Qt::BottomDockWidgetArea);
  if (auto* keyframe = qobject_cast<QDockWidget*>(keyframe_view_->parentWidget())) {
    tabifyDockWidget(keyframe, images_dock_);
  }
}

void MainWindow::AddImagesEntries(QMenu* inspect) {
  QAction* extract = NewAction(QStringLiteral("extractFeatures"), QStringLiteral("E&xtract features"), this,
                               [this] { front_end_->Extract(); });
  extract->setToolTip(
      QStringLiteral("Run the visual front end on the survey's images (SIFT, stereo and temporal matching, RANSAC, "
                     "tracks) with the parameters in force; its features replace the survey's"));
  inspect->addAction(extract);
}

void MainWindow::UpdateImagesActions() {
  if (QAction* a = action(QStringLiteral("extractFeatures"))) a->setEnabled(front_end_ && front_end_->CanExtract());
}

void MainWindow::ConnectImages() {
  auto update_survey = [this] {
    const auto& survey = session_->survey();
    images_->SetSurvey(survey ? survey->bundle : nullptr, session_->frontEnd());
  };
  connect(session_, &Session::surveyChanged, this, update_survey);
  connect(session_, &Session::featuresChanged, this, [this, update_survey] {
    update_survey();
    // The scene's landmarks are the new features' (initial triangulation).
    const auto& survey = session_->survey();
    scene_->SetSurvey(survey ? survey->bundle : nullptr, survey ? survey->overlays : nullptr);
    scene_->SetModelPose(session_->ModelPose());
    summary_->Update(*session_);
    UpdatePlacement();
    if (const auto& fe = session_->frontEnd()) {
      statusBar()->showMessage(QStringLiteral("Features extracted: %1 landmarks, %2 observations, %3 s")
                                   .arg(fe->landmarks)
                                   .arg(fe->features.size())
                                   .arg(fe->seconds, 0, 'f', 1),
                               8000);
      if (!session_->adjustment()) {
        images_dock_->show();
        images_dock_->raise();
      }
    }
    UpdateActions();
  });
  connect(session_, &Session::adjustmentChanged, this, [this] {
    const auto& run = session_->adjustment();
    images_->SetAdjustment(run ? run->result : nullptr);
  });
  connect(parameters_, &ParameterPanel::parametersChanged, front_end_, &FrontEndController::SetParameters);
  front_end_->SetParameters(parameters_->values());
  connect(front_end_, &FrontEndController::stateChanged, this, &MainWindow::UpdateActions);
}

}  // namespace hull::ui
