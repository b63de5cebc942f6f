// Pearson's chi-square test of a direction sampler against its density, as
// Mitsuba 3's and pbrt-v4's BSDF tests do: sampled directions are binned on
// a (theta, phi) grid of the whole sphere, the expected counts are the
// density integrated over each bin (adaptive Gauss-Legendre cubature), bins of
// expected count < 5 are pooled, and the p-value comes from the regularised
// upper incomplete gamma function. Samples that yield no continuous
// direction (no sample, pdf 0, a delta lobe) fall in one extra cell whose
// expectation is 1 - the density's integral.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace kappa::test::chi2 {

inline constexpr double kPi = std::numbers::pi;

/// Regularised lower incomplete gamma P(a, x) by its series (x < a + 1).
inline double gamma_p_series(double a, double x) {
  double ap = a, sum = 1.0 / a, del = sum;
  for (int n = 0; n < 100000; ++n) {
    ap += 1.0;
    del *= x / ap;
    sum += del;
    if (std::abs(del) < std::abs(sum) * 1e-15) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

/// Regularised upper incomplete gamma Q(a, x) by its continued fraction
/// (x >= a + 1), modified Lentz (Numerical Recipes, gcf).
inline double gamma_q_fraction(double a, double x) {
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-15) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

/// Q(a, x) = 1 - P(a, x) = Gamma(a, x) / Gamma(a).
inline double gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  return x < a + 1.0 ? 1.0 - gamma_p_series(a, x) : gamma_q_fraction(a, x);
}

/// P(X >= chi2) for X chi-square distributed with dof degrees of freedom.
inline double chi2_pvalue(double chi2, int dof) { return dof <= 0 ? 1.0 : gamma_q(0.5 * dof, 0.5 * chi2); }

/// The per-test level that keeps the family-wise error at `alpha` over `tests` tests.
inline double sidak(double alpha, int tests) { return 1.0 - std::pow(1.0 - alpha, 1.0 / tests); }

inline Vec3f spherical(double theta, double phi) {
  const double s = std::sin(theta);
  return Vec3f{float(s * std::cos(phi)), float(s * std::sin(phi)), float(std::cos(theta))};
}

/// 4 x 4 Gauss-Legendre on [x0, x1] x [y0, y1]: an open rule, so that a
/// density that jumps on a bin's edge (the horizon) is never read there.
template <typename F>
double gauss_legendre(const F& f, double x0, double x1, double y0, double y1) {
  constexpr double x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  constexpr double w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  const double hx = 0.5 * (x1 - x0), hy = 0.5 * (y1 - y0), cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  double sum = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) sum += w[i] * w[j] * f(cx + hx * x[i], cy + hy * x[j]);
  return sum * hx * hy;
}

/// Adaptive cubature of f(x, y) over a rectangle whose rule gave `whole`:
/// quartered until the quarters agree with the whole to eps (or to 1e-3
/// relative: the densities are floats, whose rounding would otherwise keep
/// a peak's pieces from ever agreeing), at most `depth` times.
template <typename F>
double adaptive_rect(const F& f, double x0, double x1, double y0, double y1, double whole, double eps, int depth) {
  const double xm = 0.5 * (x0 + x1), ym = 0.5 * (y0 + y1);
  const double q[4] = {gauss_legendre(f, x0, xm, y0, ym), gauss_legendre(f, xm, x1, y0, ym),
                       gauss_legendre(f, x0, xm, ym, y1), gauss_legendre(f, xm, x1, ym, y1)};
  const double sum = q[0] + q[1] + q[2] + q[3];
  if (depth <= 0 || std::abs(sum - whole) <= std::max(eps, 1e-3 * std::abs(sum))) return sum;
  return adaptive_rect(f, x0, xm, y0, ym, q[0], 0.5 * eps, depth - 1) +
         adaptive_rect(f, xm, x1, y0, ym, q[1], 0.5 * eps, depth - 1) +
         adaptive_rect(f, x0, xm, ym, y1, q[2], 0.5 * eps, depth - 1) +
         adaptive_rect(f, xm, x1, ym, y1, q[3], 0.5 * eps, depth - 1);
}

/// Nodes splitting [a, b] into `pieces` and at every split point inside.
inline std::vector<double> split_nodes(double a, double b, int pieces, const std::vector<double>& splits) {
  std::vector<double> nodes;
  for (int i = 0; i <= pieces; ++i) nodes.push_back(a + (b - a) * i / pieces);
  for (double s : splits)
    if (s > a && s < b) nodes.push_back(s);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

struct Grid {
  int n_theta = 12, n_phi = 24;
  int bins() const { return n_theta * n_phi; }
  double theta_step() const { return kPi / n_theta; }
  double phi_step() const { return 2.0 * kPi / n_phi; }
  int bin(const Vec3f& w) const {
    const double z = std::clamp(double(w.z) / std::sqrt(double(dot(w, w))), -1.0, 1.0);
    double phi = std::atan2(double(w.y), double(w.x));
    if (phi < 0.0) phi += 2.0 * kPi;
    const int t = std::min(n_theta - 1, int(std::acos(z) / theta_step()));
    const int p = std::min(n_phi - 1, int(phi / phi_step()));
    return t * n_phi + p;
  }
};

/// The density `pdf` (over solid angle) integrated over each bin; `peaks`
/// are directions near which it may be too narrow for the first nodes.
inline std::vector<double> integrate_bins(const std::function<float(const Vec3f&)>& pdf, const Grid& grid,
                                          const std::vector<Vec3f>& peaks, double eps = 1e-6) {
  // A mesh graded towards each peak (splits at geometric distances from
  // it, in the bins near it), so that a lobe narrower than a bin by orders
  // of magnitude (rough glass of index 1.01) is seen by the first nodes.
  struct Peak {
    double theta, phi, phi_scale;
    std::vector<double> theta_splits, phi_splits;
  };
  constexpr double kReach = 0.1;
  std::vector<Peak> grading;
  for (const Vec3f& w : peaks) {
    Peak pk;
    pk.theta = std::acos(std::clamp(double(w.z), -1.0, 1.0));
    pk.phi = std::atan2(double(w.y), double(w.x));
    if (pk.phi < 0.0) pk.phi += 2.0 * kPi;
    pk.phi_scale = 1.0 / std::max(std::sin(pk.theta), 0.05);
    pk.theta_splits.push_back(pk.theta);
    pk.phi_splits.push_back(pk.phi);
    for (double d = 1e-4; d < kReach; d *= 3.0)
      for (double sign : {-1.0, 1.0}) {
        pk.theta_splits.push_back(pk.theta + sign * d);
        pk.phi_splits.push_back(pk.phi + sign * d * pk.phi_scale);
      }
    grading.push_back(pk);
  }
  const auto phi_distance = [](double a, double b) {
    const double d = std::abs(a - b);
    return std::min(d, 2.0 * kPi - d);
  };
  std::vector<double> expected(grid.bins());
  const auto f = [&](double theta, double phi) { return double(pdf(spherical(theta, phi))) * std::sin(theta); };
  for (int t = 0; t < grid.n_theta; ++t) {
    const double t0 = t * grid.theta_step(), t1 = (t + 1) * grid.theta_step();
    for (int p = 0; p < grid.n_phi; ++p) {
      const double p0 = p * grid.phi_step(), p1 = (p + 1) * grid.phi_step();
      std::vector<double> theta_splits, phi_splits;
      for (const Peak& pk : grading) {
        const bool near_theta = pk.theta > t0 - kReach && pk.theta < t1 + kReach;
        const bool near_phi = pk.phi_scale * kReach >= kPi || (pk.phi >= p0 && pk.phi <= p1) ||
                              std::min(phi_distance(pk.phi, p0), phi_distance(pk.phi, p1)) < pk.phi_scale * kReach;
        if (!near_theta || !near_phi) continue;
        theta_splits.insert(theta_splits.end(), pk.theta_splits.begin(), pk.theta_splits.end());
        phi_splits.insert(phi_splits.end(), pk.phi_splits.begin(), pk.phi_splits.end());
      }
      const std::vector<double> ts = split_nodes(t0, t1, 2, theta_splits);
      const std::vector<double> ps = split_nodes(p0, p1, 2, phi_splits);
      const double piece_eps = eps / double((ts.size() - 1) * (ps.size() - 1));
      double sum = 0;
      for (std::size_t i = 0; i + 1 < ts.size(); ++i)
        for (std::size_t j = 0; j + 1 < ps.size(); ++j)
          sum += adaptive_rect(f, ts[i], ts[i + 1], ps[j], ps[j + 1],
                               gauss_legendre(f, ts[i], ts[i + 1], ps[j], ps[j + 1]), piece_eps, 10);
      expected[t * grid.n_phi + p] = sum;
    }
  }
  return expected;
}

struct Result {
  double chi2 = 0, pvalue = 1;
  int dof = 0;
  bool empty_bin_hit = false;  ///< samples where the density integrates to 0
  std::string message;
};

/// Pearson's test of `observed` against `expected` (same total, one entry
/// per cell), pooling cells of expected count below `min_expected` as pbrt-v4.
inline Result pearson(const std::vector<double>& observed, const std::vector<double>& expected, double total,
                      double min_expected = 5.0) {
  std::vector<std::size_t> order(expected.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return expected[a] < expected[b]; });
  Result r;
  double pooled_obs = 0, pooled_exp = 0;
  int cells = 0;
  for (std::size_t i : order) {
    const double o = observed[i], e = expected[i];
    if (e <= 0.0) {
      if (o > total * 1e-5) {
        r.empty_bin_hit = true;
        r.message += "cell " + std::to_string(i) + " expects 0 but has " + std::to_string(o) + "; ";
      }
      pooled_obs += o;  // a few stray samples (float rounding at a boundary)
    } else if (e < min_expected || (pooled_exp > 0.0 && pooled_exp < min_expected)) {
      pooled_obs += o;
      pooled_exp += e;
    } else {
      r.chi2 += (o - e) * (o - e) / e;
      ++cells;
    }
  }
  if (pooled_exp > 0.0 || pooled_obs > 0.0) {
    const double e = std::max(pooled_exp, 1e-12);
    r.chi2 += (pooled_obs - e) * (pooled_obs - e) / e;
    ++cells;
  }
  r.dof = cells - 1;
  r.pvalue = r.empty_bin_hit ? 0.0 : chi2_pvalue(r.chi2, r.dof);
  return r;
}

}  // namespace kappa::test::chi2
