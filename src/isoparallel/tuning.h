// The tuning constants of the isoparallel solver (isoparallel.h), all in one place: each with one
// line on why it has its value. The measurements behind them are in docs/paper_notes.md ("General
// targets"); the stage that reads each is named in its group's heading.
#pragma once

#include <limits>

namespace plateball::internal::isoparallel {

// ---------------------------------------------------------------- rolling tables (all stages)
// The nodes of a table: Magnus steps per curvature period and longest step. The rolling along a
// candidate is in closed form everywhere but in the shape scan (one Magnus table per shape); the
// crossings of the circle are found on tables of positions only.
struct Accuracy {
  int steps_per_period;
  double max_step;
};
// The shape scan's table and the coarse crossing nodes: rolling errors ~2e-5 rad, far below a scan residual.
constexpr Accuracy kSearch{12, 0.5};
// The fine crossing nodes of a hand-off near a tangency, where the chord reaches the radius between coarse nodes.
constexpr Accuracy kPolish{160, 0.02};
// Node cap of one table, the tables' own default: a shape that needs more is skipped (Valid() false).
constexpr int kTableMaxSteps = 200000;
// Relative forward-difference step: about the square root of the closed-form rolling's error (~1e-13).
constexpr double kDifferenceStep = 1e-6;

// ---------------------------------------------------------------- dispatch (solve.cc)
// Family enumerations, the length doubled after an empty one: the first length already turns the ball any angle.
constexpr int kFamilyPasses = 4;
// Shooting passes, each lengthening the search to the cap found (or doubling it): the cap settles once one is found.
constexpr int kShootingPasses = 3;

// ---------------------------------------------------------------- free-length search (search.cc)
// A run this close to a root is converged at the search accuracy: the polish finishes it.
constexpr double kSearchStop = 3e-6;
// The crossing residual a handed-off run may have: the polish converges from there.
constexpr double kSearchAccept = 1e-4;
// Runs still searching after 20 iterations rarely converge, and a longer search costs up to twice the evaluations.
constexpr int kSearchIterations = 20;
// The iterations after which a run far from a root is judged (kHopelessResidual).
constexpr int kTriageIterations = 8;
// A run still above this after kTriageIterations almost never converges: dropping it saves most of the cost.
constexpr double kHopelessResidual = 0.5;
// 100x kSearchAccept: the crossing residual adds the chord miss times the rolling's Lipschitz constant.
constexpr double kHandOffResidual = 1e-2;
// A near-tangency run (no crossing near its length) below this is handed off at its own length: the polish decides.
constexpr double kTangentHandOff = 1e-3;
// "The same solution" at the search accuracy (kSearchAccept): hand-off crossings and known results.
constexpr double kSearchSameTol = 1e-4;
// The crossings of one start or scan row searched: bounds the searches a single shape can start.
constexpr int kMaxCrossingsPerStart = 12;
// Below this residual a run whose Gauss-Newton root estimate is a known solution stops: only there is it reliable.
constexpr double kDuplicateResidual = 0.1;
// Relative distance of "the same root" in (rate, atanh k, phase, L): well inside a root's basin.
constexpr double kDuplicateTol = 3e-3;
// Above this residual the rate and modulus columns are Broyden updates (two rollings fewer); at 0.1 a root is lost.
constexpr double kSecantResidual = 0.3;
// A run whose residual fell by less than this factor twice running has stalled: a root at a fold still halves it.
constexpr double kStallRatio = 0.95;
// Below this residual no run counts as stalled: it is well within the hand-off (kHandOffResidual).
constexpr double kStallFloor = 1e-5;

// The largest modulus of a start or shape: the search (in atanh k) moves on towards the separatrix from there.
constexpr double kStartMaxModulus = 0.97;

// ---------------------------------------------------------------- polish (search.cc)
// A polish that ended between the tolerance and this lies in the valley of nearly straight short arcs.
constexpr double kValleyResidual = 1e-5;
// Secant steps of the valley polish: the secant converges superlinearly, so more means no root nearby.
constexpr int kValleySteps = 12;
// LM iterations of each valley solve in (atanh k, phase, L): it starts at the previous rate's solution.
constexpr int kValleyInnerIterations = 15;
// The valley's secant step stays within this factor of the last rate: the rate keeps its sign.
constexpr double kValleyMaxFactor = 1.5;
// The valley's first secant point, relative to the polish's rate: a small step on the curve.
constexpr double kValleyFirstStep = 2e-2;

// ---------------------------------------------------------------- shape scan (shape_scan.cc)
// Scan points with a rotation residual up to this (rad) start a search: the scan's local minima near a root.
constexpr double kScanResidual = 1.0;
// The residual of a scan point proved above kScanResidual (no logarithm taken): it never starts a search.
constexpr double kAboveScanResidual = std::numeric_limits<double>::infinity();
// A chord extremum within this of the radius is a near-tangency, where fold pairs of solutions sit.
constexpr double kTangencyMiss = 0.3;
// The first batch of shapes is small: the length cap is unknown until a solution is found.
constexpr int kFirstShapeBatch = 32;
// Later batches: large enough to keep the threads busy, small enough for the cap to shrink often.
constexpr int kShapeBatch = 256;
// Relative margin on the cap when the search length shrinks to it: the cap's own solutions stay inside.
constexpr double kCapMargin = 1e-6;
// The fewest nodes a row skip is tried for: a shorter skip costs more than the nodes it saves.
constexpr long kMinSkip = 3;

// ---------------------------------------------------------------- twin search (twins.cc)
// Continuation step in (rate, atanh k, phase, L): short enough for the corrector from the tangent predictor.
constexpr double kTwinStep = 0.15;
// Steps each way along the curve (1.2 in the unknowns): a fold pair's twin lies near its solution.
constexpr int kTwinSteps = 8;
// The corrector's tolerance on |H|: the twin's search converges from there.
constexpr double kTwinCurveTol = 1e-3;
// The corrector's Newton steps: a corrector that needs more has left the curve, and the step is halved.
constexpr int kTwinCorrections = 4;
// A branch whose |g| grows beyond this has left the neighbourhood of a twin.
constexpr double kTwinGiveUp = 1.0;
// A twin starts within kTwinSteps x kTwinStep of its solution: none of a solution beyond the cap by more.
constexpr double kTwinReach = 2 * kTwinSteps * kTwinStep;

// ---------------------------------------------------------------- merge (merge.cc)
// Relative tolerance of "the same solution" (lengths, G, E) between polished results: above their round-off.
constexpr double kSameTol = 1e-7;
// A path this near (relative) a whole number of periods may be a family: above the polish's tolerance.
constexpr double kWholePeriodTol = 1e-6;
// A path within this (relative) of its chord is the straight segment: only a straight path is as short.
constexpr double kStraightTol = 1e-9;
// A phase-shifted path with a residual below this still solves the target: the path is a family.
constexpr double kFamilyTol = 1e-8;

}  // namespace plateball::internal::isoparallel
