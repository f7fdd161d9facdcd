// Internal: the branch and bound of the certificate over one window of shape parameters (the
// driver of the tests in the other src/certify/ headers), and its result. The boxes, bounds,
// targets, residuals and options it works with are the vocabulary (certify/vocabulary.h), which
// the tests include; only the drivers (this one, certify/coverage.h and the public entry
// CertifyIsoparallel in certify/certificate.cc) include the tests.
#pragma once

#include <string>
#include <vector>

#include "certify/vocabulary.h"

namespace plateball::internal {

enum class CertifyStatus { kNotRun, kCertified, kUnaccounted, kBudgetExhausted, kInvalidInput, kInterrupted };
std::string ToString(CertifyStatus status);

struct CertifyWindowResult {
  CertifyStatus status = CertifyStatus::kNotRun;
  long boxes = 0;  // examined
  long excluded_by_chord = 0;
  long excluded_by_rotation = 0;
  long excluded_by_costate = 0;
  long excluded_by_closed_rolling = 0;   // of excluded_by_rotation: only with the closed-form bound
  long excluded_by_chart_rolling = 0;    // of excluded_by_rotation: only with the theta/2 chart's bound
  long excluded_by_centred_rolling = 0;  // of excluded_by_rotation: only with the centred form, after those
  long excluded_by_fixed_periods = 0;    // of excluded_by_chord/rotation: only with the fixed-periods bounds
  long accounted = 0;                    // boxes inside, or small undecided ones meeting, a known neighbourhood
  long unaccounted = 0;                  // small undecided boxes outside every known neighbourhood
  std::vector<int> matched;              // per known solution: how many accounted boxes it explains
  long first_order_tried = 0;            // boxes given the first-order tests (with an enclosure)
  long excluded_first_order = 0;         // by the mean-value form or a Krawczyk image disjoint from the box
  /// One per path proved (Krawczyk) to be the only solution of its box (a box of the subdivision,
  /// or, for a solution on a face of the subdivision, a box of the same size centred at its Newton
  /// point: boxes inside it are then resolved), in canonical form
  /// (CanonicalSolution); a path proved again in a box one phase period away (the same path, or
  /// within kSamePathTolerance of it) is counted in found_repeated instead.
  std::vector<CertifyPoint> found;
  std::vector<int> found_known;  // per found solution: the known one whose neighbourhood holds it, or -1
  long found_repeated = 0;
  long inside_found = 0;         // boxes inside a box proved to hold exactly one found solution
  double resolved_volume = 0.0;  // fraction of the window's volume excluded or accounted
  CertifyBox first_unaccounted;
  std::string message;
  bool Certified() const { return status == CertifyStatus::kCertified; }
};

/// Branch and bound over the window: every box lies inside the `match` neighbourhood of a known
/// solution, or is excluded (TestBox, the chord part with the smaller of D and the closed-form
/// chord bound; then the costate test, certify/costate.h), or is split along the axis with the largest share of D,
/// until D <= accept_deviation; such a small undecided box must meet a known neighbourhood (phase
/// modulo the period). kCertified: every solution of the window lies within `match` of a known
/// one (rigorous up to `margin` on the centre residuals; uniqueness inside a neighbourhood is not
/// proved). With first_order, kCertified means: every solution of the window lies within `match`
/// of a known one or is one of `found`, each the only solution in its box (an empty known list
/// is then allowed).
CertifyWindowResult CertifyWindow(const CertifyTarget& target,
                                  const std::vector<CertifyPoint>& known,
                                  const CertifyWindowOptions& options);

}  // namespace plateball::internal
