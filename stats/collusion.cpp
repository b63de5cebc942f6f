#include "collusion.h"

#include <cmath>

namespace kappa {

CollusionStats collusion(std::span<const std::uint64_t> visits, std::span<const std::uint32_t> theta,
                         std::uint64_t rays) {
  CollusionStats s;
  s.N_c = theta.size();
  s.N_r = rays;
  if (s.N_c == 0) return s;
  const double n = double(s.N_c);
  const double inv_rays = rays > 0 ? 1.0 / double(rays) : 0.0;
  double sum_p = 0, sum_t = 0, sum_pt = 0;
  for (std::size_t i = 0; i < theta.size(); ++i) {
    const double p = double(visits[i]) * inv_rays;
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
    const double dp = double(visits[i]) * inv_rays - s.p_avg, dt = double(theta[i]) - s.theta_avg;
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

}  // namespace kappa
