// Internal: fast Jacobi elliptic functions for the closed-form elastica (elastica.h).
#pragma once

#include "plateball/elastica.h"  // internal::JacobiAgm

namespace plateball::internal {

/// sn(u, k), cn(u, k), dn(u, k) for 0 <= k < 1 (descending Landen / AGM; ~1e-15 accurate for
/// |u| up to a few periods; callers reduce u modulo 4K first).
void JacobiSnCnDn(double u, double k, double* sn, double* cn, double* dn);
/// The same with the modulus' AGM sequence precomputed.
void JacobiSnCnDn(double u, const JacobiAgm& agm, double* sn, double* cn, double* dn);

}  // namespace plateball::internal
