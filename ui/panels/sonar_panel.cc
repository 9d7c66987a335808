#include "ui/panels/sonar_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFile>
#include <QFileInfo>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSlider>
#include <QSplitter>
#include <QStandardItemModel>
#include <QTimer>
#include <QVBoxLayout>
#include <cmath>

#include "base/error.h"
#include "results/sonar_files.h"
#include "sonar/sonar_consistency.h"
#include "ui/views/plot_widget.h"
#include "ui/views/sonar_fan_view.h"
#include "ui/views/sonar_view.h"

namespace hull::ui {

const QString SonarPanel::kSonarJob = QStringLiteral("sonar");

namespace {

constexpr int kStepMs = 500;  // playback: one step per half second

PlotData ErrorPlot(const SonarRun* run, int step, const QString& title, const QString& y_label, const QString& a_name,
                   const QColor& a_colour, const QString& b_name, double (*a)(const SonarStepErrors&),
                   double (*b)(const SonarStepErrors&)) {
  PlotData d;
  d.title = title;
  d.x_label = QStringLiteral("step");
  d.y_label = y_label;
  if (!run) {
    d.empty_text = QStringLiteral("Open a sonar sequence (File menu) or the sonar demo (Help menu)");
    return d;
  }
  if (!run->result.has_truth) {
    d.empty_text = QStringLiteral("This sequence has no truth: there are no errors to plot");
    return d;
  }
  PlotSeries sa, sb;
  sa.name = a_name;
  sa.colour = a_colour;
  sb.name = b_name;
  sb.colour = QColor(130, 130, 130);
  sb.dashed = true;
  for (const SonarStepRecord& r : run->result.steps) {
    if (!r.errors) continue;
    const double x = static_cast<double>(r.estimate.step);
    sa.points.emplace_back(x, a(*r.errors));
    if (b) sb.points.emplace_back(x, b(*r.errors));
  }
  d.series.push_back(sa);
  if (b) d.series.push_back(sb);
  PlotSeries dots = sa;
  dots.name.clear();
  dots.style = PlotSeries::Style::kPoints;
  d.series.push_back(dots);
  d.markers.push_back({static_cast<double>(step), QStringLiteral("step %1").arg(step), QColor(200, 120, 0)});
  return d;
}

}  // namespace

SonarPanel::SonarPanel(JobRunner* jobs, QWidget* parent) : QWidget(parent), jobs_(jobs) {
  setObjectName(QStringLiteral("sonarPanel"));
  auto* outer = new QVBoxLayout(this);
  outer->setContentsMargins(4, 4, 4, 4);
  outer->setSpacing(2);
  // First row: what runs.
  auto* row = new QHBoxLayout;
  title_ = new QLabel(QStringLiteral("No sequence"), this);
  title_->setObjectName(QStringLiteral("sonarTitle"));
  source_ = new QComboBox(this);
  source_->setObjectName(QStringLiteral("sonarSource"));
  source_->addItem(QStringLiteral("Features from the images"), true);
  source_->addItem(QStringLiteral("Given measurements (measurements.csv)"), false);
  source_->setToolTip(
      QStringLiteral("Detect, associate and track the features in the acoustic images (version 2 sequences), or "
                     "use the measurements with their given correspondences."));
  init_ = new QComboBox(this);
  init_->setObjectName(QStringLiteral("sonarInit"));
  init_->addItem(QStringLiteral("Elevation hypotheses (ours)"), static_cast<int>(SonarInit::kHypotheses));
  init_->addItem(QStringLiteral("Elevation 0 (Mai et al.)"), static_cast<int>(SonarInit::kPaper));
  init_->setToolTip(
      QStringLiteral("How a feature enters the filter when first seen: at elevation 0 with a wide "
                     "prior (the paper), or after weighing elevation hypotheses over a few views."));
  smoother_ = new QCheckBox(QStringLiteral("Batch smoother"), this);
  smoother_->setObjectName(QStringLiteral("sonarSmoother"));
  smoother_->setToolTip(
      QStringLiteral("After the EKF, a Ceres adjustment over every pose, feature, control and "
                     "measurement, with covariances"));
  estimates_ = new QComboBox(this);
  estimates_->setObjectName(QStringLiteral("sonarEstimates"));
  estimates_->addItem(QStringLiteral("3-D: filter"));
  estimates_->addItem(QStringLiteral("3-D: smoother"));
  scale_ = new QDoubleSpinBox(this);
  scale_->setObjectName(QStringLiteral("sonarEllipsoidScale"));
  scale_->setRange(1.0, 100.0);
  scale_->setDecimals(0);
  scale_->setPrefix(QStringLiteral("×"));
  scale_->setToolTip(QStringLiteral("Ellipsoids are drawn at 3σ times this factor"));
  look_ = new QComboBox(this);
  look_->setObjectName(QStringLiteral("sonarLook"));
  look_->addItem(QStringLiteral("Look at the features"));
  look_->addItem(QStringLiteral("Look at the whole run"));
  row->addWidget(title_);
  row->addWidget(source_);
  row->addWidget(init_);
  row->addWidget(smoother_);
  row->addStretch(1);
  row->addWidget(estimates_);
  row->addWidget(new QLabel(QStringLiteral("ellipsoids 3σ"), this));
  row->addWidget(scale_);
  row->addWidget(look_);
  outer->addLayout(row);
  // Second row: playback and the fan's settings.
  auto* play_row = new QHBoxLayout;
  back_ = new QPushButton(QStringLiteral("◀"), this);
  back_->setObjectName(QStringLiteral("sonarStepBack"));
  back_->setToolTip(QStringLiteral("One step back"));
  play_ = new QPushButton(QStringLiteral("Play"), this);
  play_->setObjectName(QStringLiteral("sonarPlay"));
  forward_ = new QPushButton(QStringLiteral("▶"), this);
  forward_->setObjectName(QStringLiteral("sonarStepForward"));
  forward_->setToolTip(QStringLiteral("One step forward"));
  for (QPushButton* b : {back_, forward_}) b->setMaximumWidth(36);
  slider_ = new QSlider(Qt::Horizontal, this);
  slider_->setObjectName(QStringLiteral("sonarStep"));
  step_label_ = new QLabel(this);
  step_label_->setMinimumWidth(90);
  zoom_ = new QComboBox(this);
  zoom_->setObjectName(QStringLiteral("sonarFanZoom"));
  zoom_->addItem(QStringLiteral("Fan: whole"));
  zoom_->addItem(QStringLiteral("Fan: around the features"));
  fan_scale_ = new QDoubleSpinBox(this);
  fan_scale_->setObjectName(QStringLiteral("sonarFanEllipseScale"));
  fan_scale_->setRange(1.0, 20.0);
  fan_scale_->setDecimals(0);
  fan_scale_->setPrefix(QStringLiteral("×"));
  fan_scale_->setToolTip(QStringLiteral("The fan's ellipses are drawn at 2σ times this factor"));
  play_row->addWidget(back_);
  play_row->addWidget(play_);
  play_row->addWidget(forward_);
  play_row->addWidget(slider_, 1);
  play_row->addWidget(step_label_);
  play_row->addWidget(zoom_);
  play_row->addWidget(new QLabel(QStringLiteral("ellipses 2σ"), this));
  play_row->addWidget(fan_scale_);
  outer->addLayout(play_row);

  auto* split = new QSplitter(Qt::Horizontal, this);
  fan_ = new SonarFanView(split);
  auto* left = new QWidget(split);
  auto* left_layout = new QVBoxLayout(left);
  left_layout->setContentsMargins(0, 0, 0, 0);
  view_ = new SonarView(left);
  left_layout->addWidget(view_, 1);
  legend_ = new QLabel(left);
  legend_->setWordWrap(true);
  left_layout->addWidget(legend_);
  auto* plots = new QWidget(split);
  auto* grid = new QGridLayout(plots);
  grid->setContentsMargins(0, 0, 0, 0);
  feature_plot_ = new PlotWidget(plots);
  position_plot_ = new PlotWidget(plots);
  orientation_plot_ = new PlotWidget(plots);
  feature_plot_->setObjectName(QStringLiteral("sonarFeaturePlot"));
  position_plot_->setObjectName(QStringLiteral("sonarPositionPlot"));
  orientation_plot_->setObjectName(QStringLiteral("sonarOrientationPlot"));
  // Two rows of plots: each may be smaller than a plot's own minimum, so the
  // dock keeps its height.
  for (PlotWidget* plot : {feature_plot_, position_plot_, orientation_plot_}) plot->setMinimumSize(160, 90);
  grid->addWidget(feature_plot_, 0, 0, 1, 2);
  grid->addWidget(position_plot_, 1, 0);
  grid->addWidget(orientation_plot_, 1, 1);
  split->addWidget(fan_);
  split->addWidget(left);
  split->addWidget(plots);
  split->setStretchFactor(0, 2);
  split->setStretchFactor(1, 2);
  split->setStretchFactor(2, 2);
  split->setSizes({420, 420, 440});
  outer->addWidget(split, 1);
  status_ = new QLabel(this);
  status_->setObjectName(QStringLiteral("sonarStatus"));
  outer->addWidget(status_);

  timer_ = new QTimer(this);
  timer_->setInterval(kStepMs);
  connect(timer_, &QTimer::timeout, this, [this] {
    if (!run_ || step_ + 1 >= run_->steps()) {
      Pause();
      return;
    }
    SetStep(step_ + 1);
    if (step_ + 1 >= run_->steps()) Pause();  // stops at the end
  });
  connect(play_, &QPushButton::clicked, this, [this] { playing() ? Pause() : Play(); });
  connect(back_, &QPushButton::clicked, this, &SonarPanel::StepBack);
  connect(forward_, &QPushButton::clicked, this, &SonarPanel::StepForward);
  connect(slider_, &QSlider::valueChanged, this, [this](int value) {
    if (value != step_) SetStep(value);
  });
  connect(scale_, qOverload<double>(&QDoubleSpinBox::valueChanged), view_, &SonarView::SetEllipsoidScale);
  connect(fan_scale_, qOverload<double>(&QDoubleSpinBox::valueChanged), fan_, &SonarFanView::SetEllipseScale);
  connect(zoom_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this](int index) {
    fan_->SetZoom(index == 1 ? SonarFanView::Zoom::kFeatures : SonarFanView::Zoom::kWholeFan);
  });
  connect(look_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this](int index) { view_->ResetCamera(index == 1); });
  connect(estimates_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this](int index) {
    view_->SetSmoother(index == 1);
    UpdateControls();
  });
  for (QComboBox* box : {init_, source_}) {
    connect(box, qOverload<int>(&QComboBox::currentIndexChanged), this, [this] { Rerun(); });
  }
  connect(smoother_, &QCheckBox::toggled, this, [this] { Rerun(); });
  // In the dock the fan is small: it opens on the ranges where the features are.
  zoom_->setCurrentIndex(1);
  UpdateControls();
  UpdatePlots();
}

void SonarPanel::StartFromLoader(const QString& title, std::function<std::shared_ptr<const SonarJobInput>()> load) {
  SonarJobOptions options;
  options.init = static_cast<SonarInit>(init_->currentData().toInt());
  options.from_images = source_->currentData().toBool();
  options.smoother = smoother_->isChecked();
  options.tuning = tuning_;
  jobs_->Run<std::shared_ptr<const SonarRun>>(
      kSonarJob, title,
      [load = std::move(load), options](Progress& progress) {
        progress.Update(0.0, "reading the acoustic sequence");
        std::shared_ptr<const SonarJobInput> input = load();
        progress.ThrowIfCancelled();
        progress.Update(0.1, options.smoother ? "running the sonar EKF and the smoother" : "running the sonar EKF");
        SubProgress p(progress, 0.1, 1.0);
        return std::make_shared<const SonarRun>(RunSonarJob(input, options, p));
      },
      [this](std::shared_ptr<const SonarRun>& run) { SetRun(run); });
}

void SonarPanel::OpenSequence(const QString& directory) {
  const std::string path = QFile::encodeName(directory).toStdString();
  const std::string name = QDir(directory).dirName().toStdString();
  StartFromLoader(QStringLiteral("Open the sonar sequence %1").arg(QDir(directory).dirName()),
                  [path, name] { return std::make_shared<const SonarJobInput>(ReadSonarJobInput(path, name)); });
}

void SonarPanel::OpenResults(const QString& directory) {
  const std::string path = QFile::encodeName(directory).toStdString();
  jobs_->Run<std::shared_ptr<const SonarRun>>(
      kSonarJob, QStringLiteral("Open the sonar results %1").arg(QDir(directory).dirName()),
      [path](Progress& progress) { return std::make_shared<const SonarRun>(ReadSonarRun(path, progress)); },
      [this](std::shared_ptr<const SonarRun>& run) {
        // The controls as the results were run, without running them again.
        const QSignalBlocker b1(init_), b2(source_), b3(smoother_);
        init_->setCurrentIndex(init_->findData(static_cast<int>(run->options.init)));
        source_->setCurrentIndex(source_->findData(run->options.from_images));
        smoother_->setChecked(run->options.smoother);
        SetRun(run);
      });
}

void SonarPanel::SetTuning(const SonarPipelineOptions& tuning, const QString& key) {
  if (key == tuning_key_) return;
  const bool first = tuning_key_.isEmpty();
  tuning_ = tuning;
  tuning_key_ = key;
  if (!first) Rerun();  // the run on screen, with the new tuning
}

void SonarPanel::SaveResults(const QString& folder, bool force) {
  const std::shared_ptr<const SonarRun> run = run_;
  const OutputFolder out{QFile::encodeName(QDir::cleanPath(QFileInfo(folder).absoluteFilePath())).toStdString(), force};
  jobs_->Start(QStringLiteral("sonar-save"), QStringLiteral("Save the sonar results"), [run, out](Progress& progress) {
    if (!run || !run->pipeline) {
      throw OptionError("sonar results",
                        "only a run of a sequence read from a folder can be saved (the results name it)");
    }
    progress.Update(0, "writing the sonar results");
    ResultsRun record = NewResultsRun("gui sonar");
    record.AddSequence("sequence", run->pipeline->sequence);
    SaveSonarResults(*run->pipeline, out, std::move(record));
  });
}

void SonarPanel::OpenDemo(const QString& preset) {
  const std::string p = preset.toStdString();
  StartFromLoader(QStringLiteral("Simulate the sonar demo (%1)").arg(preset),
                  [p] { return std::make_shared<const SonarJobInput>(SimulateSonarJobInput(p, 1)); });
}

void SonarPanel::OpenInput(std::shared_ptr<const SonarJobInput> input) {
  const QString name = QString::fromStdString(input->name);
  StartFromLoader(QStringLiteral("Run the sonar sequence %1").arg(name), [input] { return input; });
}

void SonarPanel::Rerun() {
  if (!run_ || !run_->input) return;
  const std::shared_ptr<const SonarJobInput> input = run_->input;
  StartFromLoader(QStringLiteral("Run the sonar EKF"), [input] { return input; });
}

void SonarPanel::SetRun(std::shared_ptr<const SonarRun> run) {
  Pause();
  run_ = std::move(run);
  const SonarConsistency consistency = run_ ? CheckSonarConsistency(run_->result) : SonarConsistency{};
  consistency_ = QString::fromStdString(consistency.Verdict());
  inconsistent_ = consistency.inconsistent;
  step_ = run_ && run_->steps() > 0 ? run_->steps() - 1 : 0;
  view_->SetRun(run_);
  view_->SetStep(step_);
  view_->ResetCamera(look_->currentIndex() == 1);
  fan_->SetRun(run_);
  fan_->SetStep(step_);
  if (run_ && run_->smoother && smoother_->isChecked()) estimates_->setCurrentIndex(1);
  if (run_ && !run_->smoother) estimates_->setCurrentIndex(0);
  view_->SetSmoother(estimates_->currentIndex() == 1);
  UpdateControls();
  UpdatePlots();
  emit runChanged();
}

void SonarPanel::SetStep(int step) {
  if (!run_ || run_->steps() == 0) return;
  step_ = std::clamp(step, 0, run_->steps() - 1);
  view_->SetStep(step_);
  fan_->SetStep(step_);
  UpdateControls();
  UpdatePlots();
}

void SonarPanel::StepForward() {
  Pause();
  SetStep(step_ + 1);
}

void SonarPanel::StepBack() {
  Pause();
  SetStep(step_ - 1);
}

void SonarPanel::Play() {
  if (!run_ || run_->steps() == 0) return;
  if (step_ + 1 >= run_->steps()) SetStep(0);
  timer_->start();
  UpdateControls();
}

void SonarPanel::Pause() {
  timer_->stop();
  UpdateControls();
}

bool SonarPanel::playing() const { return timer_->isActive(); }

void SonarPanel::UpdateControls() {
  const bool has = run_ && run_->steps() > 0;
  for (QWidget* w : std::initializer_list<QWidget*>{play_, slider_, back_, forward_}) w->setEnabled(has);
  if (has) {
    back_->setEnabled(step_ > 0);
    forward_->setEnabled(step_ + 1 < run_->steps());
  }
  play_->setText(playing() ? QStringLiteral("Pause") : QStringLiteral("Play"));
  {
    const QSignalBlocker block(slider_);
    slider_->setRange(0, has ? run_->steps() - 1 : 0);
    slider_->setValue(step_);
  }
  {
    // The choices this run offers, without running again.
    const QSignalBlocker block_source(source_);
    const bool images =
        run_ && run_->sequence->image && run_->input && (!run_->input->directory.empty() || run_->input->images);
    const bool measurements = run_ && run_->sequence->has_measurements;
    // A sequence that offers one source only leaves the choice as it was (the next one may offer both).
    source_->setEnabled(images && measurements);
    if (images && measurements) source_->setCurrentIndex(run_->from_images ? 0 : 1);
    auto* model = qobject_cast<QStandardItemModel*>(estimates_->model());
    if (model) model->item(1)->setEnabled(run_ && run_->smoother);
  }
  const bool smoothed = run_ && run_->smoother && estimates_->currentIndex() == 1;
  legend_->setText(
      QStringLiteral("<span style='color:#33d94d'>●</span> true &nbsp; ") +
      (smoothed ? QString() : QStringLiteral("<span style='color:#4d80ff'>●</span> first estimate &nbsp; ")) +
      QStringLiteral("<span style='color:#ff4033'>●</span> %1 (3σ ellipsoids) &nbsp; trajectory: "
                     "<span style='color:#33d94d'>━</span> true <span style='color:#a6a6a6'>━</span> dead reckoning "
                     "<span style='color:#ff4d40'>━</span> %2")
          .arg(smoothed ? QStringLiteral("smoothed (final)") : QStringLiteral("estimate"),
               smoothed ? QStringLiteral("smoother") : QStringLiteral("EKF")) +
      (run_ && run_->scene ? QStringLiteral(" &nbsp; <span style='color:#8c949e'>■</span> scene") : QString()));
  if (!has) {
    title_->setText(QStringLiteral("No sequence"));
    step_label_->clear();
    status_->setText(QStringLiteral("File ▸ Open sonar sequence… or Help ▸ Open sonar demo."));
    return;
  }
  title_->setText(QString::fromStdString(run_->name));
  step_label_->setText(QStringLiteral("step %1 / %2").arg(step_).arg(run_->steps() - 1));
  const SonarStepRecord& r = run_->result.steps[step_];
  QString text = QStringLiteral(
                     "Step %1: %2 measurements, %3 used, %4 features entered, %5 waiting for their "
                     "elevation.")
                     .arg(r.estimate.step)
                     .arg(r.estimate.measurements)
                     .arg(r.estimate.updated)
                     .arg(r.estimate.initialised)
                     .arg(r.estimate.pending);
  if (r.errors) {
    text += QStringLiteral(" Mean feature error %1 m; sonar position error %2 m (dead reckoning %3 m).")
                .arg(r.errors->mean_feature_error, 0, 'f', 4)
                .arg(r.errors->position, 0, 'f', 4)
                .arg(r.errors->dr_position, 0, 'f', 4);
  }
  if (run_->smoother && run_->smoother->errors) {
    text += QStringLiteral(" Smoother: final mean feature error %1 m.")
                .arg(run_->smoother->errors->mean_feature_error, 0, 'f', 4);
  }
  // The run's own consistency, first and in red when its sigma cannot be trusted.
  if (inconsistent_) {
    text = QStringLiteral(
               "<span style='color:#d62728'><b>The estimate is INCONSISTENT</b></span> (its σ "
               "understate the errors; hover for why). ") +
           text.toHtmlEscaped();
  }
  status_->setToolTip(QStringLiteral("Consistency (the EKF's innovations against χ², no truth needed): ") +
                      consistency_);
  status_->setText(text);
}

void SonarPanel::UpdatePlots() {
  const SonarRun* run = run_.get();
  feature_plot_->SetData(ErrorPlot(
      run, step_, QStringLiteral("Feature error"), QStringLiteral("m"), QStringLiteral("mean"), QColor(220, 60, 50),
      QStringLiteral("largest"), [](const SonarStepErrors& e) { return e.mean_feature_error; },
      [](const SonarStepErrors& e) { return e.max_feature_error; }));
  position_plot_->SetData(ErrorPlot(
      run, step_, QStringLiteral("Sonar position error"), QStringLiteral("m"), QStringLiteral("EKF"),
      QColor(220, 60, 50), QStringLiteral("odometry"), [](const SonarStepErrors& e) { return e.position; },
      [](const SonarStepErrors& e) { return e.dr_position; }));
  orientation_plot_->SetData(ErrorPlot(
      run, step_, QStringLiteral("Sonar orientation error"), QStringLiteral("degrees"), QStringLiteral("EKF"),
      QColor(220, 60, 50), QStringLiteral("odometry"),
      [](const SonarStepErrors& e) { return e.rotation * 180.0 / M_PI; },
      [](const SonarStepErrors& e) { return e.dr_rotation * 180.0 / M_PI; }));
}

}  // namespace hull::ui
