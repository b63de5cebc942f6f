// grid2's virtual queries (its walk with nothing recorded), its report
// section and its leaves as a CellLayout.
#include "grid2.h"

#include <nlohmann/json.hpp>

#include <algorithm>

#include "grid2_traverse.h"

namespace kappa {

std::optional<Hit> NestedGrid::closest_hit(const Ray& ray) const {
  NoRecorder none;
  return closest_hit(ray, none);
}

bool NestedGrid::any_hit(const Ray& ray) const {
  NoRecorder none;
  return any_hit(ray, none);
}

std::optional<Hit> NestedGrid::closest_hit(const Ray& ray, const FunctionHitFilter& filter) const {
  NoRecorder none;
  return closest_hit(ray, none, filter);
}

bool NestedGrid::any_hit(const Ray& ray, const FunctionHitFilter& filter) const {
  NoRecorder none;
  return any_hit(ray, none, filter);
}

std::vector<std::uint32_t> NestedGrid::occupancies() const {
  std::vector<std::uint32_t> theta(m_info.leaves);
  for (std::uint64_t i = 0; i < m_info.leaves; ++i) theta[i] = m_offsets[i + 1] - m_offsets[i];
  return theta;
}

CellBox NestedGrid::cell_box(std::uint64_t i) const {
  std::call_once(m_boxes_once, [this] {
    // Down every tree, with the walk's arithmetic: a sub-grid's cells are
    // its cell's size over n from its low corner.
    m_leaf_boxes.resize(m_info.leaves);
    const GridInfo& g = m_info.top;
    const auto visit = [this](auto&& self, std::uint32_t index, const Vec3d& lo, const Vec3d& size) -> void {
      const Node& node = m_nodes[index];
      if (node.kind != refined) {
        m_leaf_boxes[m_leaf_of_node[index]] = {lo, lo + size};
        return;
      }
      const Vec3d l{sub_cell_size(size.x, node.n[0]), sub_cell_size(size.y, node.n[1]), sub_cell_size(size.z, node.n[2])};
      std::uint32_t child = node.index;
      for (int z = 0; z < node.n[2]; ++z)
        for (int y = 0; y < node.n[1]; ++y)
          for (int x = 0; x < node.n[0]; ++x, ++child)
            self(self, child, lo + Vec3d{double(x), double(y), double(z)} * l, l);
    };
    std::uint64_t c = 0;
    for (int z = 0; z < g.resolution.nz; ++z)
      for (int y = 0; y < g.resolution.ny; ++y)
        for (int x = 0; x < g.resolution.nx; ++x, ++c)
          visit(visit, std::uint32_t(c), g.lo + Vec3d{double(x), double(y), double(z)} * g.cell_size, g.cell_size);
  });
  return m_leaf_boxes[i];
}

std::string NestedGrid::resolution_text() const {
  return m_info.top.resolution.to_string() + " top, " + std::to_string(m_info.leaves) + " leaves in " +
         std::to_string(m_info.levels) + " levels";
}

std::vector<CellLayout::Level> NestedGrid::levels() const {
  std::vector<Level> out;
  for (int k = 0; k < m_info.levels; ++k) out.push_back({k, m_info.level[k].N_c, m_info.level[k].theta_tot});
  return out;
}

nlohmann::ordered_json NestedGrid::report_section() const {
  const Grid2Info& g = m_info;
  nlohmann::ordered_json j;
  j["top_res"] = {g.top.resolution.nx, g.top.resolution.ny, g.top.resolution.nz};
  j["top_cell_size"] = {g.top.cell_size.x, g.top.cell_size.y, g.top.cell_size.z};
  j["refined"] = g.refined;
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
  for (int k = 0; k < g.levels; ++k)
    levels.push_back({{"level", k}, {"N_c", g.level[k].N_c}, {"theta_tot", g.level[k].theta_tot},
                      {"bytes", g.level[k].bytes}});
  j["levels"] = levels;
  return j;
}

}  // namespace kappa
