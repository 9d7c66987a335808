#include "ui/views/solver_plots_view.h"

#include <QGridLayout>
#include <QLabel>
#include <QScrollArea>
#include <QVBoxLayout>

namespace hull::ui {

SolverPlotsView::SolverPlotsView(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("solverPlotsView"));
  auto* outer = new QVBoxLayout(this);
  outer->setContentsMargins(4, 4, 4, 4);
  summary_ = new QLabel(this);
  summary_->setObjectName(QStringLiteral("solverSummary"));
  summary_->setWordWrap(true);
  summary_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  outer->addWidget(summary_);
  auto* scroll = new QScrollArea(this);
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  auto* grid_host = new QWidget(scroll);
  auto* grid = new QGridLayout(grid_host);
  grid->setContentsMargins(0, 0, 0, 0);
  grid->setSpacing(6);
  cost_ = new PlotWidget(grid_host);
  fraction_ = new PlotWidget(grid_host);
  time_ = new PlotWidget(grid_host);
  dvl_ = new PlotWidget(grid_host);
  mixture_ = new PlotWidget(grid_host);
  cost_->setObjectName(QStringLiteral("costPlot"));
  fraction_->setObjectName(QStringLiteral("fractionPlot"));
  time_->setObjectName(QStringLiteral("timePlot"));
  dvl_->setObjectName(QStringLiteral("dvlResidualPlot"));
  mixture_->setObjectName(QStringLiteral("mixturePlot"));
  // Three to a row: each wide enough for its legend; the dock scrolls when short.
  int i = 0;
  for (PlotWidget* plot : {fraction_, cost_, time_, dvl_, mixture_}) {
    plot->setMinimumSize(330, 220);
    grid->addWidget(plot, i / 3, i % 3);
    ++i;
  }
  scroll->setWidget(grid_host);
  outer->addWidget(scroll, 1);
  SetRuns(nullptr, {});
  SetSigmas(AdjustmentOptions().sigma0, AdjustmentOptions().sigma1);
}

void SolverPlotsView::SetRuns(std::shared_ptr<const AdjustmentRun> run, const RunsByModel& runs) {
  RunsByModel all = runs;
  if (run && !all.count(run->model())) all[run->model()] = run;
  cost_->SetData(CostPlot(all));
  fraction_->SetData(FractionPlot(run));
  time_->SetData(TimePlot(all));
  dvl_->SetData(DvlResidualPlot(run));
  if (!run) {
    summary_->setText(QStringLiteral("No adjustment yet: open a survey and its mesh, then Inspection ▸ Run (F5)."));
    return;
  }
  const AdjustmentResult& r = *run->result;
  QString text = QStringLiteral(
                     "<b>%1</b>: %2 iterations in %3 s (solver %4 s), cost %5 → %6; %7. %8 landmarks "
                     "(%9 left out), %10 observations rejected.")
                     .arg(ModelShortName(r.options.model))
                     .arg(r.iterations.empty() ? 0 : r.iterations.back().iteration)
                     .arg(r.seconds, 0, 'f', 2)
                     .arg(r.solver_seconds, 0, 'f', 2)
                     .arg(r.initial_cost, 0, 'g', 4)
                     .arg(r.final_cost, 0, 'g', 4)
                     .arg(r.converged ? QStringLiteral("converged") : QStringLiteral("not converged"))
                     .arg(r.landmarks.size())
                     .arg(r.num_landmarks_skipped)
                     .arg(r.observations_rejected);
  if (run->warm_started) text += QStringLiteral(" Started from the previous result.");
  if (run->evaluation) {
    const AdjustmentEvaluation& e = *run->evaluation;
    text += QStringLiteral(
                "<br>Against truth: landmark RMSE %1 cm (gauge-aligned), labels %2 % right, DVL "
                "spread %3 → %4 cm.")
                .arg(100.0 * e.landmark_rmse, 0, 'f', 2)
                .arg(100.0 * e.label_agreement, 0, 'f', 1)
                .arg(100.0 * e.dvl_mad_initial, 0, 'f', 2)
                .arg(100.0 * e.dvl_mad_final, 0, 'f', 2);
  }
  summary_->setText(text);
}

void SolverPlotsView::SetSigmas(double sigma0, double sigma1) { mixture_->SetData(MixturePlot(sigma0, sigma1)); }

QString SolverPlotsView::summaryText() const { return summary_->text(); }

}  // namespace hull::ui
