// The sonar dock: an acoustic sequence (opened from a folder, or one of the
// simulator's layouts, rendered with images, as a demo) run through the
// sonar EKF in a worker (job kind "sonar"): from the images (detection,
// association, EKF) or from measurements.csv, optionally followed by the
// batch smoother. Then played step by step: a slider, step back/forward and
// play/pause move the fan view (SonarFanView: the polar image as a fan with
// the step's detections, predictions and associations), the 3-D view
// (SonarView: the filter's or the smoother's estimates, the scene) and the
// current-step marker of the error plots — mean and largest feature error,
// and the sonar's position and orientation error against dead reckoning
// (Mai et al., Figs. 7, 8 and 11). Switching the feature source, the
// initialisation (the paper's elevation 0 or our elevation hypotheses) or
// the smoother runs the job again. Saved results (OpenResults) play the
// same way, as they were written.
#pragma once

#include <QString>
#include <QWidget>
#include <memory>

#include "ui/jobs/job_runner.h"
#include "ui/session/sonar_results.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QSlider;
class QTimer;

namespace hull::ui {

class PlotWidget;
class SonarFanView;
class SonarView;

class SonarPanel : public QWidget {
  Q_OBJECT

 public:
  static const QString kSonarJob;

  explicit SonarPanel(JobRunner* jobs, QWidget* parent = nullptr);

  // Reads the acoustic sequence folder and runs the EKF over it (a job).
  void OpenSequence(const QString& directory);
  // Simulates one of the layouts ("prism", "tank", "above") with its images and runs it.
  void OpenDemo(const QString& preset);
  // Reads a saved sonar results folder (hullinspect-cli sonar, or saved
  // from here) with its sequence and plays it (a job); the controls show
  // the options it was run with, and changing one runs the EKF again.
  void OpenResults(const QString& directory);
  // Writes the run on screen as a sonar results folder (a job), as
  // `hullinspect-cli sonar` writes one: `folder` replaced as a whole, a
  // folder of the user's files only with `force` (theirs kept). Refused,
  // through the job's failure, for a run without a sequence folder.
  void SaveResults(const QString& folder, bool force = false);
  // The chain's tuning (the parameter table's Sonar rows); `key` names the
  // values: a new key runs the sequence on screen again.
  void SetTuning(const SonarPipelineOptions& tuning, const QString& key);
  const SonarPipelineOptions& tuning() const { return tuning_; }
  // Runs a loaded input (e.g. a test's own simulation).
  void OpenInput(std::shared_ptr<const SonarJobInput> input);

  const std::shared_ptr<const SonarRun>& run() const { return run_; }
  int step() const { return step_; }
  void SetStep(int step);
  void StepForward();
  void StepBack();
  void Play();
  void Pause();
  bool playing() const;

  SonarView* view() const { return view_; }
  SonarFanView* fanView() const { return fan_; }
  PlotWidget* featurePlot() const { return feature_plot_; }
  PlotWidget* positionPlot() const { return position_plot_; }
  PlotWidget* orientationPlot() const { return orientation_plot_; }
  QComboBox* initBox() const { return init_; }
  QComboBox* sourceBox() const { return source_; }
  QCheckBox* smootherBox() const { return smoother_; }
  QComboBox* estimatesBox() const { return estimates_; }
  QComboBox* zoomBox() const { return zoom_; }

 signals:
  void runChanged();

 private:
  void Rerun();
  void StartFromLoader(const QString& title, std::function<std::shared_ptr<const SonarJobInput>()> load);
  void SetRun(std::shared_ptr<const SonarRun> run);
  void UpdatePlots();
  void UpdateControls();

  JobRunner* jobs_;
  std::shared_ptr<const SonarRun> run_;
  int step_ = 0;
  QLabel* title_ = nullptr;
  QComboBox* init_ = nullptr;
  QComboBox* source_ = nullptr;
  QCheckBox* smoother_ = nullptr;
  QComboBox* estimates_ = nullptr;
  QComboBox* zoom_ = nullptr;
  QDoubleSpinBox* fan_scale_ = nullptr;
  QLabel* legend_ = nullptr;
  QPushButton* back_ = nullptr;
  QPushButton* forward_ = nullptr;
  QPushButton* play_ = nullptr;
  QSlider* slider_ = nullptr;
  QLabel* step_label_ = nullptr;
  QDoubleSpinBox* scale_ = nullptr;
  QComboBox* look_ = nullptr;
  SonarView* view_ = nullptr;
  SonarFanView* fan_ = nullptr;
  PlotWidget* feature_plot_ = nullptr;
  PlotWidget* position_plot_ = nullptr;
  PlotWidget* orientation_plot_ = nullptr;
  QLabel* status_ = nullptr;
  QString consistency_;  // the run's CheckSonarConsistency verdict
  SonarPipelineOptions tuning_;
  QString tuning_key_;
  bool inconsistent_ = false;
  QTimer* timer_ = nullptr;
};

}  // namespace hull::ui
