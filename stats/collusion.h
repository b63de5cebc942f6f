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

/// p_i = visits_i / rays. All sums in double, in a fixed order. Empty
/// `visits` (no per-cell counts) reads as p_i = 0.
CollusionStats collusion(std::span<const std::uint64_t> visits, std::span<const std::uint32_t> theta,
                         std::uint64_t rays);

/// The same when per-cell visits were counted for only `sample_rays` of the
/// class's `rays` rays (whole paths drawn with probability q = sample_rays /
/// rays), while the class's totals cover every ray: p_tot, p_avg, refs_per_ray
/// and kappa (eq 8, as N_c * refs / (cells * theta_tot)) are then exact;
/// sigma_p, r and kappa_eq25 are estimated from the sample. sigma_p^2 uses
/// the unbiased estimate of sum_i v_i^2 from binomially thinned counts X_i,
/// sum_i (X_i^2 - (1 - q) X_i) / q^2, which is exact in expectation when no
/// path sends two rays of the class through one cell; kappa_eq25 is the
/// sample's own ratio, so its distance from kappa shows the sampling error.
/// With sample_rays == rays it is collusion(visits, theta, rays). With
/// sample_rays == 0 (and empty `visits`: per-cell counts refused) sigma_p is
/// NaN and r and kappa_eq25 are undefined; the totals' quantities stay.
CollusionStats collusion_sampled(std::span<const std::uint64_t> visits, std::span<const std::uint32_t> theta,
                                 std::uint64_t sample_rays, std::uint64_t rays, std::uint64_t cells,
                                 std::uint64_t refs);

}  // namespace kappa
