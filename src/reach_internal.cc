#include "reach_internal.h"

#include <ceres/jet.h>

#include <array>
#include <cmath>

#include "dynamics.h"

namespace plateball::internal {
namespace {

using ZxState = std::array<double, 5>;  // z[3], x[2]

struct ZxOnlyRhs {
  double lambda;
  std::array<double, 2> k;
  void operator()(const ZxState& y, ZxState& dy, double /*t*/) const {
    double w[2];
    OmegaFromZK(y.data(), k.data(), lambda, w);
    ZxRhs(y.data(), w, dy.data(), dy.data() + 3);
  }
};

Eigen::Vector2d VelocityAt(const double* z, const Eigen::Vector2d& k, double lambda) {
  const double kk[2] = {k.x(), k.y()};
  double w[2];
  OmegaFromZK(z, kk, lambda, w);
  return {w[1], -w[0]};
}

}  // namespace

void TabulatePeriod(const ReachDirection& d, double lambda, double period, int steps, ScanPeriod* out) {
  const ZxOnlyRhs rhs{lambda, {d.k.x(), d.k.y()}};
  out->x.resize(static_cast<std::size_t>(steps) + 1);
  out->v.resize(static_cast<std::size_t>(steps) + 1);
  ZxState y{d.z0.x(), d.z0.y(), d.z0.z(), 0.0, 0.0};
  const double h = period / steps;
  ZxState k1, k2, k3, k4, tmp;
  for (int j = 0;; ++j) {
    rhs(y, k1, 0.0);
    out->x[static_cast<std::size_t>(j)] = {y[3], y[4]};
    out->v[static_cast<std::size_t>(j)] = {k1[3], k1[4]};
    if (j == steps) break;
    for (int i = 0; i < 5; ++i) tmp[i] = y[i] + 0.5 * h * k1[i];
    rhs(tmp, k2, 0.0);
    for (int i = 0; i < 5; ++i) tmp[i] = y[i] + 0.5 * h * k2[i];
    rhs(tmp, k3, 0.0);
    for (int i = 0; i < 5; ++i) tmp[i] = y[i] + h * k3[i];
    rhs(tmp, k4, 0.0);
    for (int i = 0; i < 5; ++i) y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
  out->drift = out->x.back();
}

void TabulatePeriods(const ReachDirection* d, int count, double lambda, double period, int steps, ScanPeriod* out) {
  constexpr int kLanes = 4;
  int first = 0;
  for (; first + kLanes <= count; first += kLanes) {
    double y[kLanes][5], k1[kLanes][5], k2[kLanes][5], k3[kLanes][5], k4[kLanes][5], tmp[kLanes][5], kk[kLanes][2];
    for (int l = 0; l < kLanes; ++l) {
      const ReachDirection& dl = d[first + l];
      y[l][0] = dl.z0.x();
      y[l][1] = dl.z0.y();
      y[l][2] = dl.z0.z();
      y[l][3] = y[l][4] = 0.0;
      kk[l][0] = dl.k.x();
      kk[l][1] = dl.k.y();
      out[first + l].x.resize(static_cast<std::size_t>(steps) + 1);
      out[first + l].v.resize(static_cast<std::size_t>(steps) + 1);
    }
    auto rhs = [&](const double(*in)[5], double(*o)[5]) {
      for (int l = 0; l < kLanes; ++l) {
        double w[2];
        OmegaFromZK(in[l], kk[l], lambda, w);
        ZxRhs(in[l], w, o[l], o[l] + 3);
      }
    };
    const double h = period / steps;
    for (int j = 0;; ++j) {
      rhs(y, k1);
      for (int l = 0; l < kLanes; ++l) {
        out[first + l].x[static_cast<std::size_t>(j)] = {y[l][3], y[l][4]};
        out[first + l].v[static_cast<std::size_t>(j)] = {k1[l][3], k1[l][4]};
      }
      if (j == steps) break;
      for (int l = 0; l < kLanes; ++l)
        for (int i = 0; i < 5; ++i) tmp[l][i] = y[l][i] + 0.5 * h * k1[l][i];
      rhs(tmp, k2);
      for (int l = 0; l < kLanes; ++l)
        for (int i = 0; i < 5; ++i) tmp[l][i] = y[l][i] + 0.5 * h * k2[l][i];
      rhs(tmp, k3);
      for (int l = 0; l < kLanes; ++l)
        for (int i = 0; i < 5; ++i) tmp[l][i] = y[l][i] + h * k3[l][i];
      rhs(tmp, k4);
      for (int l = 0; l < kLanes; ++l)
        for (int i = 0; i < 5; ++i) y[l][i] += h / 6.0 * (k1[l][i] + 2.0 * k2[l][i] + 2.0 * k3[l][i] + k4[l][i]);
    }
    for (int l = 0; l < kLanes; ++l) out[first + l].drift = out[first + l].x.back();
  }
  for (; first < count; ++first) TabulatePeriod(d[first], lambda, period, steps, &out[first]);
}

TightPoint EvaluateTight(
    const ReachDirection& d, double lambda, double period, double t, bool with_ds, const IntegrationOptions& options) {
  const double kf = std::floor(t / period);
  const double tau = std::min(std::max(t - kf * period, 0.0), period);
  const double dt0 = period / 64.0;
  TightPoint p;
  if (!with_ds) {
    const ZxOnlyRhs rhs{lambda, {d.k.x(), d.k.y()}};
    ZxState y{d.z0.x(), d.z0.y(), d.z0.z(), 0.0, 0.0};
    IntegrateAdaptive(rhs, y, 0.0, tau, dt0, options);
    p.x = {y[3], y[4]};
    p.velocity = VelocityAt(y.data(), d.k, lambda);
    if (kf != 0.0) {
      IntegrateAdaptive(rhs, y, tau, period, dt0, options);
      p.x += kf * Eigen::Vector2d(y[3], y[4]);
    }
    return p;
  }
  const SensitivityRhs rhs{lambda, {d.k.x(), d.k.y()}, {d.dk_ds.x(), d.dk_ds.y()}};
  SensitivityState y{d.z0.x(), d.z0.y(), d.z0.z(), 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  IntegrateAdaptive(rhs, y, 0.0, tau, dt0, options);
  p.x = {y[3], y[4]};
  p.dx_ds = {y[8], y[9]};
  p.velocity = VelocityAt(y.data(), d.k, lambda);
  if (kf != 0.0) {
    IntegrateAdaptive(rhs, y, tau, period, dt0, options);
    p.x += kf * Eigen::Vector2d(y[3], y[4]);
    p.dx_ds += kf * Eigen::Vector2d(y[8], y[9]);
  }
  return p;
}

}  // namespace plateball::internal
