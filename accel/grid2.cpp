// grid2's virtual queries (its walk with nothing recorded), its report
// section and its leaves as a CellLayout.
#include "grid2.h"

#include <nlohmann/json.hpp>

#include <algorithm>

#include "grid2_traverse.h"

namespace kappa {

std::optional<Hit> TwoLevelGrid::closest_hit(const Ray& ray) const {
  NoRecorder none;
  return closest_hit(ray, none);
}

bool TwoLevelGrid::any_hit(const Ray& ray) const {
  NoRecorder none;
  return any_hit(ray, none);
}

std::uint64_t TwoLevelGrid::top_of_leaf(std::uint64_t i) const {
  // first_leaf rises strictly (every top cell has at least one leaf).
  const auto it = std::upper_bound(m_top.begin(), m_top.end(), i,
                                   [](std::uint64_t leaf, const TopCell& t) { return leaf < t.first_leaf; });
  return std::uint64_t(it - m_top.begin()) - 1;
}

CellBox TwoLevelGrid::top_box(int ix, int iy, int iz) const {
  const GridInfo& g = m_info.top;
  const Vec3d lo = g.lo + Vec3d{double(ix), double(iy), double(iz)} * g.cell_size;
  return {lo, lo + g.cell_size};
}

std::vector<std::uint32_t> TwoLevelGrid::occupancies() const {
  std::vector<std::uint32_t> theta(m_info.leaves);
  for (std::uint64_t i = 0; i < m_info.leaves; ++i) theta[i] = m_offsets[i + 1] - m_offsets[i];
  return theta;
}

CellBox TwoLevelGrid::cell_box(std::uint64_t i) const {
  const std::uint64_t c = top_of_leaf(i);
  const TopCell& top = m_top[c];
  const GridInfo sub = sub_grid(c, top);
  const std::uint64_t local = i - top.first_leaf, nx = top.n[0], ny = top.n[1];
  const Vec3d index{double(local % nx), double((local / nx) % ny), double(local / (nx * ny))};
  const Vec3d lo = sub.lo + index * sub.cell_size;
  return {lo, lo + sub.cell_size};
}

int TwoLevelGrid::cell_level(std::uint64_t i) const { return m_top[top_of_leaf(i)].occupied ? 1 : 0; }

std::string TwoLevelGrid::resolution_text() const {
  return m_info.top.resolution.to_string() + " top, " + std::to_string(m_info.leaves) + " leaves";
}

nlohmann::ordered_json TwoLevelGrid::report_section() const {
  const Grid2Info& g = m_info;
  nlohmann::ordered_json j;
  j["top_res"] = {g.top.resolution.nx, g.top.resolution.ny, g.top.resolution.nz};
  j["top_cell_size"] = {g.top.cell_size.x, g.top.cell_size.y, g.top.cell_size.z};
  j["top_occupied"] = g.top_occupied;
  j["N_c"] = g.leaves;
  j["N"] = g.N;
  j["build_s"] = g.build_s;
  j["bytes"] = g.bytes;
  j["theta_tot"] = g.theta_tot;
  j["theta_avg"] = g.leaves > 0 ? double(g.theta_tot) / double(g.leaves) : 0.0;
  j["theta_max"] = g.max_occupancy;
  j["empty_fraction"] = g.leaves > 0 ? double(g.empty_leaves) / double(g.leaves) : 0.0;
  j["degenerate"] = g.degenerate;
  nlohmann::ordered_json levels = nlohmann::ordered_json::array();
  for (const Grid2Level& level : g.levels)
    levels.push_back({{"level", level.level}, {"N_c", level.N_c}, {"theta_tot", level.theta_tot}, {"bytes", level.bytes}});
  j["levels"] = levels;
  return j;
}

}  // namespace kappa
