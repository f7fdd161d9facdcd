// Internal: how many times an elastica crosses a circle about its start, counted with a proof.
//
// f(s) = |x(s)|^2 - r^2 has f' = 2 x.t and f'' = 2 (1 + kappa x.n), and the pendulum's energy
// bounds the curvature: kappa^2 = theta'^2 = 2 (E + G cos theta) <= 2 (E + G). On [a, b] this
// bounds |f''| <= M = 2 (1 + kappa_max (|x(a)| + |x(b)| + b - a) / 2), and an interval is decided
//  - monotone, when f'(a) and f'(b) share a sign and |f'(a)| + |f'(b)| > M (b - a) (f' is
//    M-Lipschitz, so it keeps that sign): one crossing if f changes sign, else none;
//  - without a root, when f(a) and f(b) share a sign and the quadratic bounds from both ends,
//    f(a + t) >= f(a) + f'(a) t - M t^2 / 2 (and the same from b), cover [a, b] between them;
//  - else it is halved.
// Sign changes on a grid of nodes (the search tables' count) miss a pair of crossings between two
// nodes, around a near-tangency of the chord, where the isoparallel solutions often end.
#pragma once

#include "plateball/elastica.h"

namespace plateball::internal {

/// The number of roots of |x(s)| = radius for s in (0, s_end] (x(0) = 0, radius > 0), each
/// counted once. An interval is halved at most down to 1e-13 (1 + s) in length; one that is still
/// undecided there (a tangency to round-off) counts the sign change of its ends.
int CountCircleCrossings(const Elastica& e, double radius, double s_end);

}  // namespace plateball::internal
