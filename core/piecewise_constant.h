// Piecewise-constant distributions on [0, 1) and [0, 1)^2 (pbrt-v4's
// PiecewiseConstant1D/2D): a function given by its values on equal bins,
// sampled in proportion to them by inverting its CDF, with the density of
// any point. What importance-samples an environment image.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

namespace kappa {

class PiecewiseConstant1D {
 public:
  PiecewiseConstant1D() = default;
  /// Bins of non-negative weight; all zero (or none) samples uniformly.
  explicit PiecewiseConstant1D(std::span<const double> f) : m_f(f.begin(), f.end()), m_cdf(f.size() + 1, 0.0) {
    const double n = double(f.size());
    for (std::size_t i = 0; i < f.size(); ++i) m_cdf[i + 1] = m_cdf[i] + std::max(f[i], 0.0) / n;
    m_integral = m_cdf.back();
    if (m_integral > 0) {
      for (double& c : m_cdf) c /= m_integral;
    } else {
      for (std::size_t i = 0; i <= f.size(); ++i) m_cdf[i] = double(i) / n;
      std::fill(m_f.begin(), m_f.end(), 1.0);
      m_integral = 1.0;
    }
    m_cdf.back() = 1.0;
  }

  std::size_t size() const { return m_f.size(); }
  /// The function's integral over [0, 1) (1 for an all-zero one, sampled uniformly).
  double integral() const { return m_integral; }

  /// x in [0, 1) with density pdf(x); `bin` the bin it lies in.
  double sample(double u, double& pdf, std::size_t& bin) const {
    // The last bin whose CDF start is <= u, skipping empty bins.
    const auto it = std::upper_bound(m_cdf.begin(), m_cdf.end(), u);
    bin = std::size_t(std::clamp<std::ptrdiff_t>(it - m_cdf.begin() - 1, 0, std::ptrdiff_t(m_f.size()) - 1));
    while (bin > 0 && !(m_cdf[bin + 1] > m_cdf[bin])) --bin;
    const double width = m_cdf[bin + 1] - m_cdf[bin];
    double du = width > 0 ? (u - m_cdf[bin]) / width : 0.0;
    du = std::clamp(du, 0.0, std::nextafter(1.0, 0.0));  // stays in its bin: pdf() agrees
    pdf = density(bin);
    const double x = (double(bin) + du) / double(m_f.size());
    return std::min(x, std::nextafter(1.0, 0.0));
  }
  /// The density of bin i.
  double density(std::size_t i) const { return std::max(m_f[i], 0.0) / m_integral; }

 private:
  std::vector<double> m_f;
  std::vector<double> m_cdf;
  double m_integral = 0;
};

/// f(x, y) on width x height bins, row y = 0 at v = 0: a marginal over rows,
/// a conditional over each row's columns.
class PiecewiseConstant2D {
 public:
  PiecewiseConstant2D() = default;
  /// `f` holds height rows of width values.
  PiecewiseConstant2D(std::span<const double> f, std::size_t width, std::size_t height) : m_width(width) {
    std::vector<double> marginal(height);
    m_rows.reserve(height);
    for (std::size_t y = 0; y < height; ++y) {
      m_rows.emplace_back(f.subspan(y * width, width));
      marginal[y] = m_rows.back().integral();
    }
    // An all-zero row's conditional is uniform with integral 1; its marginal weight is 0.
    for (std::size_t y = 0; y < height; ++y) {
      bool zero = true;
      for (std::size_t x = 0; x < width && zero; ++x) zero = !(f[y * width + x] > 0);
      if (zero) marginal[y] = 0;
    }
    m_marginal = PiecewiseConstant1D(marginal);
  }

  /// (u, v) in [0, 1)^2 with density pdf over the unit square.
  void sample(double u0, double u1, double& u, double& v, double& pdf) const {
    double pdf_v = 0, pdf_u = 0;
    std::size_t row = 0, column = 0;
    v = m_marginal.sample(u1, pdf_v, row);
    u = m_rows[row].sample(u0, pdf_u, column);
    pdf = pdf_v * pdf_u;
  }
  double pdf(double u, double v) const {
    const std::size_t row = std::min(std::size_t(std::max(v, 0.0) * double(m_rows.size())), m_rows.size() - 1);
    const std::size_t column = std::min(std::size_t(std::max(u, 0.0) * double(m_width)), m_width - 1);
    return m_marginal.density(row) * m_rows[row].density(column);
  }

 private:
  std::size_t m_width = 0;
  std::vector<PiecewiseConstant1D> m_rows;
  PiecewiseConstant1D m_marginal;
};

}  // namespace kappa
