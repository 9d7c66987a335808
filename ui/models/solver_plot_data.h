// The solver plots' contents, built from adjustment runs (no widgets): the
// paper's Fig. 16 (features with lambda = 1 per iteration), Fig. 17 (cost and
// time per surface model), Fig. 18 (DVL range residuals at the initial
// alignment and after) and Fig. 7 (the max-mixture's two costs and its
// decision boundary).
#pragma once

#include <map>
#include <memory>

#include "ui/models/plot_data.h"
#include "ui/session/inspection_results.h"

namespace hull::ui {

using RunsByModel = std::map<SurfaceModel, std::shared_ptr<const AdjustmentRun>>;

QColor ModelColour(SurfaceModel model);
QString ModelShortName(SurfaceModel model);  // "Naive", "All on surface", "Max-mixture"

// Cost per iteration (log scale), one line per model run available.
PlotData CostPlot(const RunsByModel& runs);
// Share of landmarks with lambda = 1 per iteration of the run on screen.
PlotData FractionPlot(const std::shared_ptr<const AdjustmentRun>& run);
// Seconds per model (bars), with the time relative to the naive model.
PlotData TimePlot(const RunsByModel& runs);
// Histograms of the DVL residuals (measured - predicted) at the initial
// alignment and after the adjustment, with their robust spread.
PlotData DvlResidualPlot(const std::shared_ptr<const AdjustmentRun>& run);
// -log N(h; 0, sigma0^2) and -log N(h; 0, sigma1^2) over h, the max-mixture's
// cost (their minimum) and the decision boundary at +-DecisionBoundary().
PlotData MixturePlot(double sigma0, double sigma1);

// Robust spread 1.4826 * MAD of the finite values (0 without any).
double RobustSpread(std::vector<double> values);

}  // namespace hull::ui
