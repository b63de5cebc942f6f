#include "renderer/render/tile_costs.h"

#include <algorithm>
#include <numeric>

#include "renderer/render/pilot.h"
#include "renderer/render/tile_schedule.h"

namespace kappa {

std::vector<double> predicted_tile_costs(const Pilot& pilot, int width, int height) {
  if (pilot.width <= 0 || pilot.height <= 0 || width <= 0 || height <= 0 ||
      pilot.pixel_rays.size() != std::size_t(pilot.width) * std::size_t(pilot.height))
    return {};
  const int tiles_x = (width + kTileSize - 1) / kTileSize;
  const int tiles_y = (height + kTileSize - 1) / kTileSize;
  // The pilot pixel each frame column and row falls in (the pilot films the
  // frame's view at a smaller size, pilot.cpp).
  std::vector<int> pilot_x(std::size_t(width), 0), pilot_y(std::size_t(height), 0);
  for (int x = 0; x < width; ++x)
    pilot_x[std::size_t(x)] = std::min(pilot.width - 1, int((double(x) + 0.5) * pilot.width / width));
  for (int y = 0; y < height; ++y)
    pilot_y[std::size_t(y)] = std::min(pilot.height - 1, int((double(y) + 0.5) * pilot.height / height));
  std::vector<double> costs(std::size_t(tiles_x) * std::size_t(tiles_y), 0.0);
  for (int y = 0; y < height; ++y) {
    const std::size_t row = std::size_t(pilot_y[std::size_t(y)]) * std::size_t(pilot.width);
    double* tile_row = costs.data() + std::size_t(y / kTileSize) * std::size_t(tiles_x);
    for (int x = 0; x < width; ++x) tile_row[x / kTileSize] += double(pilot.pixel_rays[row + std::size_t(pilot_x[std::size_t(x)])]);
  }
  return costs;
}

std::vector<std::size_t> costliest_first(const std::vector<double>& costs, std::size_t tiles) {
  std::vector<std::size_t> order(tiles);
  std::iota(order.begin(), order.end(), std::size_t(0));
  if (costs.size() != tiles) return order;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return costs[a] > costs[b]; });
  return order;
}

}  // namespace kappa
