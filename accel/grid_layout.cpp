// What the grid tells reports and statistics about itself and its cells:
// apart from grid.cpp, whose translation unit holds only the walk.
#include <nlohmann/json.hpp>

#include "grid.h"

namespace kappa {

std::vector<std::uint32_t> UniformGrid::occupancies() const {
  std::vector<std::uint32_t> theta(m_info.resolution.cells());
  for (std::size_t i = 0; i < theta.size(); ++i) theta[i] = std::uint32_t(cell(i).size());
  return theta;
}

CellBox UniformGrid::cell_box(std::uint64_t i) const {
  const GridResolution& r = m_info.resolution;
  const std::uint64_t nx = std::uint64_t(r.nx), ny = std::uint64_t(r.ny);
  const Vec3d index{double(i % nx), double((i / nx) % ny), double(i / (nx * ny))};
  const Vec3d lo = m_info.lo + index * m_info.cell_size;
  return {lo, lo + m_info.cell_size};
}

nlohmann::ordered_json UniformGrid::report_section() const {
  const GridInfo& g = m_info;
  const double cells = double(g.resolution.cells());
  nlohmann::ordered_json j;
  j["res"] = {g.resolution.nx, g.resolution.ny, g.resolution.nz};
  j["N_c"] = g.resolution.cells();
  j["N"] = g.N;
  j["cell_size"] = {g.cell_size.x, g.cell_size.y, g.cell_size.z};
  j["build_s"] = g.build_s;
  j["bytes"] = g.bytes;
  j["theta_tot"] = g.theta_tot;
  j["theta_avg"] = double(g.theta_tot) / cells;
  j["theta_max"] = g.max_occupancy;
  j["max_multiplicity"] = g.max_multiplicity;
  j["empty_fraction"] = double(g.empty_cells) / cells;
  j["degenerate"] = g.degenerate;
  return j;
}

}  // namespace kappa
