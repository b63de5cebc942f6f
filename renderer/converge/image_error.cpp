#include "renderer/converge/image_error.h"

#include <cmath>
#include <stdexcept>

#include "renderer/render/pixel_samples.h"

namespace kappa {

ImageError image_error(const std::vector<float>& x, const std::vector<float>& ref) {
  if (x.size() != ref.size()) throw std::invalid_argument("image_error: the images differ in size");
  ImageError e;
  if (x.empty()) return e;
  double sq = 0, rel = 0, sum_x = 0, sum_ref = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = ref[i], d = double(x[i]) - r;
    sq += d * d;
    rel += d * d / (r * r + kRelmseEpsilon);
    sum_x += x[i];
    sum_ref += r;
  }
  const double n = double(x.size());
  e.relmse = rel / n;
  e.rmse = std::sqrt(sq / n);
  e.bias = sum_ref != 0 ? sum_x / sum_ref - 1.0 : 0.0;
  return e;
}

double relmse_floor(const std::vector<float>& ref_variance, const std::vector<float>& ref) {
  if (ref_variance.size() != ref.size()) throw std::invalid_argument("relmse_floor: the images differ in size");
  if (ref.empty()) return 0;
  double sum = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) sum += ref_variance[i] / (double(ref[i]) * ref[i] + kRelmseEpsilon);
  return sum / double(ref.size());
}

}  // namespace kappa
