// The charts of `plateball montecarlo`: the distributions of the final errors per strategy, and
// the median final error against n (log-log, fitted slopes). Drawn on SvgFigure (common/svg.h)
// with decade ticks on log axes and the legend below the plot, so that it never covers a curve.
#pragma once

#include <string>

#include "plateball/monte_carlo.h"

namespace plateball::tools {

/// Survival functions P(error > e) of the final orientation error (solid) and position error
/// (dashed) at the main n, per scenario and strategy, log-log; the plan's own error as a dotted line.
std::string RenderErrorDistributions(const MonteCarloProblem& problem,
                                     const MonteCarloSummary& summary,
                                     const NominalPlan& plan);

/// Median final orientation error against n per scenario and strategy with the fitted log-log
/// slope in the legend, and the error of the plan without errors (Theorem 2.6: slope -2).
std::string RenderErrorAgainstN(const MonteCarloProblem& problem, const MonteCarloSummary& summary);

}  // namespace plateball::tools
