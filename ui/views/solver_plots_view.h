// The solver plots dock: cost and features on the hull per iteration (the
// paper's Figs. 16 and 17), time per surface model, DVL residual histograms
// before and after (Fig. 18) and the max-mixture's cost curves with the
// decision boundary for the sigmas in force (Fig. 7), which follow the
// parameter panel as it is edited. A summary line above sums up the run.
#pragma once

#include <QWidget>
#include <memory>

#include "ui/models/solver_plot_data.h"
#include "ui/views/plot_widget.h"

class QLabel;

namespace hull::ui {

class SolverPlotsView : public QWidget {
  Q_OBJECT

 public:
  explicit SolverPlotsView(QWidget* parent = nullptr);

  // The run on screen (nullptr: none) and the runs of each model for the
  // current parameters.
  void SetRuns(std::shared_ptr<const AdjustmentRun> run, const RunsByModel& runs);
  // The max-mixture's sigmas in force.
  void SetSigmas(double sigma0, double sigma1);

  PlotWidget* costPlot() const { return cost_; }
  PlotWidget* fractionPlot() const { return fraction_; }
  PlotWidget* timePlot() const { return time_; }
  PlotWidget* dvlPlot() const { return dvl_; }
  PlotWidget* mixturePlot() const { return mixture_; }
  QString summaryText() const;

 private:
  QLabel* summary_ = nullptr;
  PlotWidget* cost_ = nullptr;
  PlotWidget* fraction_ = nullptr;
  PlotWidget* time_ = nullptr;
  PlotWidget* dvl_ = nullptr;
  PlotWidget* mixture_ = nullptr;
};

}  // namespace hull::ui
