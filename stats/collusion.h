// The collusion factor and its ingredients (seed paper, section 3 and 6.1)
// from per-cell visit counts and occupancies.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

namespace kappa {

struct CollusionStats {
  std::uint64_t N_c = 0;
  std::uint64_t N_r = 0;      ///< rays
  double p_tot = 0;           ///< sum_i p_i = mean cells per ray (eq 6)
  double p_avg = 0;           ///< p_tot / N_c (eq 7)
  double theta_tot = 0;       ///< sum_i Theta_i (eq 4)
  double theta_avg = 0;       ///< theta_tot / N_c (eq 5)
  double sigma_p = 0;         ///< population standard deviation of p_i
  double sigma_theta = 0;     ///< population standard deviation of Theta_i
  std::optional<double> r;    ///< Pearson correlation of (p_i, Theta_i); none if a sigma is 0
  std::optional<double> kappa;       ///< eq 8; none without rays or triangles
  std::optional<double> kappa_eq25;  ///< corrected eq 25: 1 + (sigma_p/p_avg)(sigma_theta/theta_avg) r
  double refs_per_ray = 0;    ///< sum_i p_i Theta_i = p_avg theta_tot kappa
};

/// p_i = visits_i / rays. All sums in double, in a fixed order.
CollusionStats collusion(std::span<const std::uint64_t> visits, std::span<const std::uint32_t> theta,
                         std::uint64_t rays);

}  // namespace kappa
