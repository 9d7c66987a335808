#include "ui/panels/sonar_panel.h"

#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFile>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSlider>
#include <QSplitter>
#include <QTimer>
#include <QVBoxLayout>
#include <cmath>

#include "simulate/sonar_simulator.h"
#include "ui/views/plot_widget.h"
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
  auto* row = new QHBoxLayout;
  title_ = new QLabel(QStringLiteral("No sequence"), this);
  title_->setObjectName(QStringLiteral("sonarTitle"));
  init_ = new QComboBox(this);
  init_->setObjectName(QStringLiteral("sonarInit"));
  init_->addItem(QStringLiteral("Elevation hypotheses (ours)"), static_cast<int>(SonarInit::kHypotheses));
  init_->addItem(QStringLiteral("Elevation 0 (Mai et al.)"), static_cast<int>(SonarInit::kPaper));
  init_->setToolTip(
      QStringLiteral("How a feature enters the filter when first seen: at elevation 0 with a wide "
                     "prior (the paper), or after weighing elevation hypotheses over a few views."));
  play_ = new QPushButton(QStringLiteral("Play"), this);
  play_->setObjectName(QStringLiteral("sonarPlay"));
  slider_ = new QSlider(Qt::Horizontal, this);
  slider_->setObjectName(QStringLiteral("sonarStep"));
  step_label_ = new QLabel(this);
  step_label_->setMinimumWidth(90);
  scale_ = new QDoubleSpinBox(this);
  scale_->setObjectName(QStringLiteral("sonarEllipsoidScale"));
  scale_->setRange(1.0, 100.0);
  scale_->setDecimals(0);
  scale_->setPrefix(QStringLiteral("×"));
  scale_->setToolTip(QStringLiteral("Ellipsoids are drawn at 3σ times this factor"));
  row->addWidget(title_);
  row->addWidget(init_);
  row->addWidget(play_);
  row->addWidget(slider_, 1);
  row->addWidget(step_label_);
  row->addWidget(new QLabel(QStringLiteral("ellipsoids 3σ"), this));
  row->addWidget(scale_);
  look_ = new QComboBox(this);
  look_->setObjectName(QStringLiteral("sonarLook"));
  look_->addItem(QStringLiteral("Look at the features"));
  look_->addItem(QStringLiteral("Look at the whole run"));
  row->addWidget(look_);
  outer->addLayout(row);

  auto* split = new QSplitter(Qt::Horizontal, this);
  auto* left = new QWidget(split);
  auto* left_layout = new QVBoxLayout(left);
  left_layout->setContentsMargins(0, 0, 0, 0);
  view_ = new SonarView(left);
  left_layout->addWidget(view_, 1);
  auto* legend = new QLabel(left);
  legend->setText(QStringLiteral(
      "<span style='color:#33d94d'>●</span> true &nbsp; <span style='color:#4d80ff'>●</span> first estimate "
      "&nbsp; <span style='color:#ff4033'>●</span> estimate (3σ ellipsoids) &nbsp; trajectory: "
      "<span style='color:#33d94d'>━</span> true <span style='color:#a6a6a6'>━</span> dead reckoning "
      "<span style='color:#ff4d40'>━</span> EKF"));
  legend->setWordWrap(true);
  left_layout->addWidget(legend);
  auto* plots = new QWidget(split);
  auto* grid = new QGridLayout(plots);
  grid->setContentsMargins(0, 0, 0, 0);
  feature_plot_ = new PlotWidget(plots);
  position_plot_ = new PlotWidget(plots);
  orientation_plot_ = new PlotWidget(plots);
  feature_plot_->setObjectName(QStringLiteral("sonarFeaturePlot"));
  position_plot_->setObjectName(QStringLiteral("sonarPositionPlot"));
  orientation_plot_->setObjectName(QStringLiteral("sonarOrientationPlot"));
  grid->addWidget(feature_plot_, 0, 0);
  grid->addWidget(position_plot_, 0, 1);
  grid->addWidget(orientation_plot_, 0, 2);
  split->addWidget(left);
  split->addWidget(plots);
  split->setStretchFactor(0, 2);
  split->setStretchFactor(1, 3);
  split->setSizes({500, 780});
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
  });
  connect(play_, &QPushButton::clicked, this, [this] { playing() ? Pause() : Play(); });
  connect(slider_, &QSlider::valueChanged, this, [this](int value) {
    if (value != step_) SetStep(value);
  });
  connect(scale_, qOverload<double>(&QDoubleSpinBox::valueChanged), view_, &SonarView::SetEllipsoidScale);
  connect(look_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this](int index) { view_->ResetCamera(index == 1); });
  connect(init_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this] {
    if (run_) Start(run_->sequence, QString::fromStdString(run_->name));
  });
  UpdateControls();
  UpdatePlots();
}

void SonarPanel::StartFromLoader(const QString& title, std::function<std::shared_ptr<const AcousticSequence>()> load,
                                 const QString& name) {
  const auto init = static_cast<SonarInit>(init_->currentData().toInt());
  jobs_->Run<std::shared_ptr<const SonarRun>>(
      kSonarJob, title,
      [load = std::move(load), init, name](Progress& progress) {
        progress.Update(0.0, "reading the acoustic sequence");
        std::shared_ptr<const AcousticSequence> sequence = load();
        progress.ThrowIfCancelled();
        progress.Update(0.1, "running the sonar EKF");
        SubProgress p(progress, 0.1, 1.0);
        return std::make_shared<const SonarRun>(RunSonarJob(sequence, name.toStdString(), init, p));
      },
      [this](std::shared_ptr<const SonarRun>& run) { SetRun(run); });
}

void SonarPanel::OpenSequence(const QString& directory) {
  const std::string path = QFile::encodeName(directory).toStdString();
  StartFromLoader(
      QStringLiteral("Open the sonar sequence %1").arg(QDir(directory).dirName()),
      [path] { return std::make_shared<const AcousticSequence>(ReadAcousticSequence(path)); },
      QDir(directory).dirName());
}

void SonarPanel::OpenDemo(const QString& preset) {
  const std::string p = preset.toStdString();
  StartFromLoader(
      QStringLiteral("Simulate the sonar demo (%1)").arg(preset),
      [p] { return std::make_shared<const AcousticSequence>(SimulateSonarPreset(p, 1)); },
      QStringLiteral("demo: %1").arg(preset));
}

void SonarPanel::Start(std::shared_ptr<const AcousticSequence> sequence, const QString& name) {
  StartFromLoader(
      QStringLiteral("Run the sonar EKF"), [sequence] { return sequence; }, name);
}

void SonarPanel::SetRun(std::shared_ptr<const SonarRun> run) {
  Pause();
  run_ = std::move(run);
  step_ = run_ && run_->steps() > 0 ? run_->steps() - 1 : 0;
  view_->SetRun(run_);
  view_->SetStep(step_);
  view_->ResetCamera(look_->currentIndex() == 1);
  UpdateControls();
  UpdatePlots();
  emit runChanged();
}

void SonarPanel::SetStep(int step) {
  if (!run_) return;
  step_ = std::clamp(step, 0, run_->steps() - 1);
  view_->SetStep(step_);
  UpdateControls();
  UpdatePlots();
}

void SonarPanel::Play() {
  if (!run_) return;
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
  play_->setEnabled(has);
  slider_->setEnabled(has);
  play_->setText(playing() ? QStringLiteral("Pause") : QStringLiteral("Play"));
  {
    const QSignalBlocker block(slider_);
    slider_->setRange(0, has ? run_->steps() - 1 : 0);
    slider_->setValue(step_);
  }
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
