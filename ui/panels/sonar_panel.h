// The sonar dock: an acoustic sequence (opened from a folder, or one of the
// simulator's layouts as a demo) run through the sonar EKF in a worker (job
// kind "sonar"), then played step by step: a slider and play/pause move
// the 3-D view (SonarView) and the current-step marker of the error plots —
// mean and largest feature error, and the sonar's position and orientation
// error against dead reckoning (Mai et al., Figs. 7, 8 and 11). The feature
// initialisation (the paper's elevation 0 or our elevation hypotheses) can
// be switched; the EKF then runs again.
#pragma once

#include <QString>
#include <QWidget>
#include <memory>

#include "ui/jobs/job_runner.h"
#include "ui/session/sonar_results.h"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QSlider;
class QTimer;

namespace hull::ui {

class PlotWidget;
class SonarView;

class SonarPanel : public QWidget {
  Q_OBJECT

 public:
  static const QString kSonarJob;

  explicit SonarPanel(JobRunner* jobs, QWidget* parent = nullptr);

  // Reads the acoustic sequence folder and runs the EKF over it (a job).
  void OpenSequence(const QString& directory);
  // Simulates one of the layouts ("prism", "tank", "above") and runs it.
  void OpenDemo(const QString& preset);

  const std::shared_ptr<const SonarRun>& run() const { return run_; }
  int step() const { return step_; }
  void SetStep(int step);
  void Play();
  void Pause();
  bool playing() const;

  SonarView* view() const { return view_; }
  PlotWidget* featurePlot() const { return feature_plot_; }
  PlotWidget* positionPlot() const { return position_plot_; }
  PlotWidget* orientationPlot() const { return orientation_plot_; }
  QComboBox* initBox() const { return init_; }

 signals:
  void runChanged();

 private:
  void Start(std::shared_ptr<const AcousticSequence> sequence, const QString& name);
  void StartFromLoader(const QString& title, std::function<std::shared_ptr<const AcousticSequence>()> load,
                       const QString& name);
  void SetRun(std::shared_ptr<const SonarRun> run);
  void UpdatePlots();
  void UpdateControls();

  JobRunner* jobs_;
  std::shared_ptr<const SonarRun> run_;
  int step_ = 0;
  QLabel* title_ = nullptr;
  QComboBox* init_ = nullptr;
  QPushButton* play_ = nullptr;
  QSlider* slider_ = nullptr;
  QLabel* step_label_ = nullptr;
  QDoubleSpinBox* scale_ = nullptr;
  QComboBox* look_ = nullptr;
  SonarView* view_ = nullptr;
  PlotWidget* feature_plot_ = nullptr;
  PlotWidget* position_plot_ = nullptr;
  PlotWidget* orientation_plot_ = nullptr;
  QLabel* status_ = nullptr;
  QTimer* timer_ = nullptr;
};

}  // namespace hull::ui
