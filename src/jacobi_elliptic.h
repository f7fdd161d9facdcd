// Internal: fast Jacobi elliptic functions for the closed-form elastica (elastica.h).
#pragma once

namespace plateball::internal {

/// The arithmetic-geometric mean sequence of the modulus k (depends on k only): computed once
/// per elastica, it leaves the per-argument work of JacobiSnCnDn to one sincos and a short
/// descending recursion.
struct JacobiAgm {
  explicit JacobiAgm(double k = 0.0);
  double k = 0.0;
  double c = 1.0;  // final AGM value
  int levels = 0;  // index of the last level
  double em[16] = {}, en[16] = {};
};

/// sn(u, k), cn(u, k), dn(u, k) for 0 <= k < 1 (descending Landen / AGM; ~1e-15 accurate for
/// |u| up to a few periods; callers reduce u modulo 4K first).
void JacobiSnCnDn(double u, double k, double* sn, double* cn, double* dn);
/// The same with the modulus' AGM sequence precomputed.
void JacobiSnCnDn(double u, const JacobiAgm& agm, double* sn, double* cn, double* dn);

}  // namespace plateball::internal
