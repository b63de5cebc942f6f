#include "collusion.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.h"

namespace kappa {

CollusionStats collusion(std::span<const std::uint64_t> visits, std::span<const std::uint32_t> theta,
                         std::uint64_t rays) {
  // One visit count per cell, or none at all (per-cell counts refused): a
  // shorter array would be read past its end below.
  if (!visits.empty()) KAPPA_CHECK_EQ(visits.size(), theta.size());
  CollusionStats s;
  s.N_c = theta.size();
  s.N_r = rays;
  if (s.N_c == 0) return s;
  const double n = double(s.N_c);
  const double inv_rays = rays > 0 && !visits.empty() ? 1.0 / double(rays) : 0.0;
  // No per-cell counts (empty visits) reads as p_i = 0 everywhere.
  const auto visits_at = [&](std::size_t i) { return visits.empty() ? 0.0 : double(visits[i]); };
  double sum_p = 0, sum_t = 0, sum_pt = 0;
  for (std::size_t i = 0; i < theta.size(); ++i) {
    const double p = visits_at(i) * inv_rays;
    sum_p += p;
    sum_t += theta[i];
    sum_pt += p * theta[i];
  }
  s.p_tot = sum_p;
  s.p_avg = sum_p / n;
  s.theta_tot = sum_t;
  s.theta_avg = sum_t / n;
  s.refs_per_ray = sum_pt;
  // Second moments about the means (two-pass: stable for sparse grids).
  double var_p = 0, var_t = 0, cov = 0;
  for (std::size_t i = 0; i < theta.size(); ++i) {
    const double dp = visits_at(i) * inv_rays - s.p_avg, dt = double(theta[i]) - s.theta_avg;
    var_p += dp * dp;
    var_t += dt * dt;
    cov += dp * dt;
  }
  s.sigma_p = std::sqrt(var_p / n);
  s.sigma_theta = std::sqrt(var_t / n);
  if (s.p_tot > 0 && s.theta_tot > 0) {
    s.kappa = n * sum_pt / (s.p_tot * s.theta_tot);  // eq 8
    if (s.sigma_p > 0 && s.sigma_theta > 0) {
      s.r = (cov / n) / (s.sigma_p * s.sigma_theta);
      s.kappa_eq25 = 1.0 + (s.sigma_p / s.p_avg) * (s.sigma_theta / s.theta_avg) * *s.r;
    } else {
      s.kappa_eq25 = 1.0;  // uniform p or Theta: no collusion, as eq 8 gives too
    }
  }
  return s;
}

CollusionStats collusion_sampled(std::span<const std::uint64_t> visits, std::span<const std::uint32_t> theta,
                                 std::uint64_t sample_rays, std::uint64_t rays, std::uint64_t cells,
                                 std::uint64_t refs) {
  KAPPA_CHECK_LE(sample_rays, rays);
  if (sample_rays >= rays) return collusion(visits, theta, rays);
  // The sample alone, as if it were the whole class: its Theta moments are
  // the grid's, its p moments and covariance are estimates.
  CollusionStats s = collusion(visits, theta, sample_rays);
  const double p_avg_sample = s.p_avg;
  s.N_r = rays;
  if (s.N_c == 0) return s;
  const double n = double(s.N_c);
  const double Rs = double(sample_rays);
  const double q = rays > 0 ? Rs / double(rays) : 0.0;
  // Exact, from the totals of every ray.
  s.p_tot = rays > 0 ? double(cells) / double(rays) : 0.0;
  s.p_avg = s.p_tot / n;
  s.refs_per_ray = rays > 0 ? double(refs) / double(rays) : 0.0;
  s.kappa.reset();
  if (s.p_tot > 0 && s.theta_tot > 0) s.kappa = n * s.refs_per_ray / (s.p_tot * s.theta_tot);
  if (sample_rays == 0) {
    s.sigma_p = std::numeric_limits<double>::quiet_NaN();  // nothing sampled: unknown (null in reports)
    s.r.reset();
    s.kappa_eq25.reset();
    return s;
  }
  // sigma_p from the unbiased estimate of sum_i p_i^2.
  double sum_p2 = 0;
  for (const std::uint64_t v : visits) {
    const double x = double(v);
    sum_p2 += x * x - (1.0 - q) * x;
  }
  sum_p2 /= Rs * Rs;
  // About the sample's own mean: the sample's size then cancels out of the
  // spread, where the exact mean would leave its noise in it.
  s.sigma_p = std::sqrt(std::max(0.0, sum_p2 / n - p_avg_sample * p_avg_sample));
  // r and kappa_eq25 from the sample's covariance (collusion() above),
  // r rescaled to the estimated sigma_p (and kept in [-1, 1]: the sample's
  // covariance keeps its noise while the corrected sigma_p loses its bias).
  if (s.sigma_p == 0) {
    s.r.reset();
    if (s.kappa_eq25) s.kappa_eq25 = 1.0;  // uniform p: no collusion, as collusion() gives
  } else if (s.kappa_eq25 && s.r) {
    const double cov = (*s.kappa_eq25 - 1.0) * p_avg_sample * s.theta_avg;
    s.r = std::clamp(cov / (s.sigma_p * s.sigma_theta), -1.0, 1.0);
  }
  return s;
}

}  // namespace kappa
