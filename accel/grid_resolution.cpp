#include "grid_resolution.h"

#include <charconv>
#include <cmath>

#include "core/input_error.h"

namespace kappa {

std::string GridResolution::to_string() const {
  return std::to_string(nx) + "x" + std::to_string(ny) + "x" + std::to_string(nz);
}

std::optional<GridResolution> parse_grid_resolution(std::string_view text) {
  if (text == "auto") return std::nullopt;
  int values[3];
  int count = 0;
  std::size_t start = 0;
  while (true) {
    const std::size_t x = text.find('x', start);
    const std::string_view part = text.substr(start, x == std::string_view::npos ? std::string_view::npos : x - start);
    int v = 0;
    const auto [p, ec] = std::from_chars(part.data(), part.data() + part.size(), v);
    if (count == 3 || part.empty() || ec != std::errc() || p != part.data() + part.size() || v < 1 || v > kMaxGridAxis)
      throw InputError("--grid-res: '" + std::string(text) + "' is not auto, N or NxNxN with 1 <= N <= " +
                                  std::to_string(kMaxGridAxis));
    values[count++] = v;
    if (x == std::string_view::npos) break;
    start = x + 1;
  }
  if (count == 1) return GridResolution{values[0], values[0], values[0]};
  if (count == 3) return GridResolution{values[0], values[1], values[2]};
  throw InputError("--grid-res: '" + std::string(text) + "' needs 1 or 3 numbers");
}

GridResolution choose_resolution(const Vec3d& extent, double target_cells) {
  const double largest = max_component(extent);
  if (!(largest > 0) || !(target_cells > 1)) return {};
  auto resolution_for = [&](double cell) {
    GridResolution r;
    int* axes[3] = {&r.nx, &r.ny, &r.nz};
    for (int a = 0; a < 3; ++a) {
      const double n = std::round(extent[a] / cell);
      *axes[a] = int(std::clamp(n, 1.0, double(kMaxGridAxis)));
    }
    return r;
  };
  // The cell count falls as the cell side grows: bisect (in log space) for
  // the side whose count is closest to the target.
  double small = largest / kMaxGridAxis, big = largest;
  GridResolution a = resolution_for(small), b = resolution_for(big);
  // Most boxes are near-cubic: a bracket of 4x around the side of cubic
  // cells of the target count saves the dozen steps from the whole range.
  // Taken only if its ends hold the bisection's invariant (more cells than
  // the target at the small end, at most the target at the big end), so the
  // count's one crossing of the target lies inside it and the answer is the
  // same as from the whole range.
  double volume = 1;
  for (int k = 0; k < 3; ++k) volume *= std::max(extent[k], small);
  const double guess = std::cbrt(volume / target_cells);
  if (guess / 2 > small && guess * 2 < big) {
    const GridResolution guess_a = resolution_for(guess / 2), guess_b = resolution_for(guess * 2);
    if (double(guess_a.cells()) > target_cells && !(double(guess_b.cells()) > target_cells))
      small = guess / 2, big = guess * 2, a = guess_a, b = guess_b;
  }
  for (int i = 0; i < 100; ++i) {
    // Done once a has more cells than the target and b differs from it by
    // one step on one axis: every side between them then resolves to a or
    // b, so the remaining steps would keep both (the grid2 build calls this
    // for every cell it refines, and all 100 steps were a quarter of it).
    if (double(a.cells()) > target_cells && (a.nx - b.nx) + (a.ny - b.ny) + (a.nz - b.nz) <= 1) break;
    const double mid = std::sqrt(small * big);
    const GridResolution r = resolution_for(mid);
    if (double(r.cells()) > target_cells) small = mid, a = r;
    else big = mid, b = r;
  }
  const double da = std::abs(std::log(double(a.cells()) / target_cells));
  const double db = std::abs(std::log(double(b.cells()) / target_cells));
  return da < db ? a : b;
}

}  // namespace kappa
