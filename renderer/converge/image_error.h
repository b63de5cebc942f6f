// How far an image is from a reference, as the samplers issue and the budgets
// measure it: relMSE is the mean over pixels and the R, G, B channels of
// (x - ref)^2 / (ref^2 + 0.01) (the 0.01, kRelmseEpsilon, keeps black pixels
// from dominating, as in the budgets' estimate); RMSE the root of the mean of
// (x - ref)^2; the bias of the mean image mean(x) / mean(ref) - 1.
#pragma once

#include <vector>

namespace kappa {

struct ImageError {
  double relmse = 0;
  double rmse = 0;
  double bias = 0;  ///< mean(x) / mean(ref) - 1 (0 when the reference is black)
};

/// `x` and `ref` are RGB triples of the same size, summed in double.
ImageError image_error(const std::vector<float>& x, const std::vector<float>& ref);

/// The reference's own share of an image's relMSE: the mean of
/// var_ref / (ref^2 + 0.01), from its variance-of-the-mean channels. An image
/// that equalled the true mean would read this against the reference.
double relmse_floor(const std::vector<float>& ref_variance, const std::vector<float>& ref);

}  // namespace kappa
