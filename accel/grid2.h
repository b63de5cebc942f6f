// grid2: a nested grid, exact like the uniform grid. A coarse top grid over
// the scene (Kalojanov, Billeter & Slusallek, "Two-Level Grids for Ray
// Tracing on GPUs", EG 2011); each top cell that holds more than a few
// triangles is its own uniform sub-grid sized by its triangle count, and a
// sub-grid cell that still holds many is refined again (Jevans & Wyvill,
// "Adaptive voxel subdivision for ray tracing", GI 1989), up to
// kMaxGrid2Levels levels. A small detailed object in a large box (the teapot
// in a stadium) gets fine cells where its triangles are, while empty space is
// crossed one top cell at a time.
//
// The leaves are what statistics call cells: a top cell or sub-grid cell that
// is not refined, of the level it sits at (0 = a top cell). The leaves tile
// the box without overlap, so a walk visits each leaf it crosses once, in
// order along the ray, and eq 8's kappa reads them as it reads a uniform
// grid's cells (stats/README.md, "grid2").
//
// Exactness follows the uniform grid's argument (grid.h): every cell of every
// level is a closed box inflated by the same insertion margin, a closest-hit
// walk stops only after the leaf whose exit lies beyond the hit by that
// margin, and the triangle test is the one shared function.
#pragma once

#include <array>
#include <cstdint>
#include <mutex>
#include <optional>
#include <span>
#include <vector>

#include "accel.h"
#include "cell_layout.h"
#include "core/huge_pages.h"
#include "core/task_progress.h"
#include "grid.h"
#include "grid_resolution.h"
#include "recorder.h"

namespace kappa {

/// Default top density, top cells per triangle, and leaf density, a
/// sub-grid's cells per triangle of the cell it refines: measured with
/// tools/grid2_density_sweep.sh (top 1/32 .. 1/2, leaf 1 .. 8, kappa bench
/// against Embree) on the Cornell box, Sponza, the bunny and the teapot in a
/// stadium, where 1/2 and 2 came within about 10 % of each scene's best
/// setting (the spread of repeated runs) while leaf densities of 4 and more
/// were slower everywhere and took 2-5x the memory.
inline constexpr double kDefaultGrid2TopDensity = 0.5;
inline constexpr double kDefaultGrid2LeafDensity = 2.0;
/// A cell holding more triangles than this is refined into a sub-grid (while
/// levels remain); at or below it, it stays a leaf.
inline constexpr std::uint32_t kGrid2LeafTriangles = 8;
/// Levels at most: the top grid and three of sub-grids (the teapot in the
/// stadium, 6,400 triangles in one 500-unit top cell, needs all four).
inline constexpr int kMaxGrid2Levels = kMaxCellLevels;
/// A sub-grid's most cells per axis (its resolution is stored in bytes).
inline constexpr int kMaxSubAxis = 255;

namespace detail {
inline constexpr auto kInverseAxis = [] {
  std::array<double, kMaxSubAxis + 1> inverse{};
  for (int i = 1; i <= kMaxSubAxis; ++i) inverse[std::size_t(i)] = 1.0 / i;
  return inverse;
}();
}  // namespace detail

/// A sub-grid cell's size along an axis, its parent cell's over n: by a
/// table, so that the walk divides nowhere, and the same in the build, the
/// walk and the cells' boxes.
inline double sub_cell_size(double size, int n) { return size * detail::kInverseAxis[std::size_t(n)]; }

struct Grid2Options {
  double top_density = kDefaultGrid2TopDensity;
  double leaf_density = kDefaultGrid2LeafDensity;
  std::uint64_t max_bytes = default_grid_max_bytes();
};

/// One level of grid2, for reports: its leaves, their total occupancy, and
/// the bytes of its cells' records and lists.
struct Grid2Level {
  int level = 0;
  std::uint64_t N_c = 0;
  std::uint64_t theta_tot = 0;
  std::uint64_t bytes = 0;
};

struct Grid2Info {
  GridInfo top;               ///< the top grid: resolution, box, cell size, margin (its lists are not kept)
  std::uint64_t N = 0;        ///< triangles in the structure
  std::uint64_t degenerate = 0;
  std::uint64_t refined = 0;  ///< cells of any level split into a sub-grid
  std::uint64_t leaves = 0;   ///< N_c over every level
  std::uint64_t theta_tot = 0;     ///< references over all leaves
  std::uint32_t max_occupancy = 0;
  std::uint64_t empty_leaves = 0;
  std::uint64_t bytes = 0;
  double build_s = 0;
  int levels = 1;             ///< levels that hold leaves (1 .. kMaxGrid2Levels)
  Grid2Level level[kMaxGrid2Levels];
};

class NestedGrid final : public Accelerator, public CellLayout {
 public:
  /// Throws InputError if the structure would exceed options.max_bytes or
  /// 2^32 - 1 cells or references.
  NestedGrid(std::span<const Triangle> triangles, const Grid2Options& options, TaskProgress* progress = nullptr);

  std::optional<Hit> closest_hit(const Ray& ray) const override;
  bool any_hit(const Ray& ray) const override;
  std::optional<Hit> closest_hit(const Ray& ray, const FunctionHitFilter& filter) const override;
  bool any_hit(const Ray& ray, const FunctionHitFilter& filter) const override;
  std::string_view name() const override { return "grid2"; }
  AccelKind kind() const override { return AccelKind::grid2; }
  std::uint64_t bytes() const override { return m_info.bytes; }
  std::uint64_t reference_bytes() const override { return m_info.theta_tot * sizeof(TriangleId); }
  double build_s() const override { return m_info.build_s; }
  /// The report's "grid2" section (stats/README.md).
  nlohmann::ordered_json report_section() const override;
  const CellLayout* cells() const override { return this; }

  // CellLayout: the leaves, numbered top cell by top cell (x fastest, then
  // y, then z), each refined cell's leaves in its sub-grid's order.
  std::uint64_t cell_count() const override { return m_info.leaves; }
  std::vector<std::uint32_t> occupancies() const override;
  CellBox cell_box(std::uint64_t i) const override;
  int cell_level(std::uint64_t i) const override { return m_leaf_level[i]; }
  CellBox bounds() const override { return {m_info.top.lo, m_info.top.hi}; }
  std::optional<Vec3d> uniform_cell_size() const override { return std::nullopt; }
  std::string resolution_text() const override;
  std::vector<Level> levels() const override;

  /// The queries with a recorder (accel/recorder.h; the walk is in grid2_traverse.h).
  /// With a filter (hit_filter.h), asked of every candidate hit the walk's
  /// tests find, in the walk's order.
  template <class Recorder, HitFilter Filter = NoHitFilter>
  std::optional<Hit> closest_hit(const Ray& ray, Recorder& recorder, const Filter& filter = {}) const;
  template <class Recorder, HitFilter Filter = NoHitFilter>
  bool any_hit(const Ray& ray, Recorder& recorder, const Filter& filter = {}) const;
  /// The any-hit walk, returning the triangle that stopped it (kNoTriangle
  /// if nothing did): what an occluder cache keeps.
  template <class Recorder, HitFilter Filter = NoHitFilter>
  TriangleId occluder_of(const Ray& ray, Recorder& recorder, const Filter& filter = {}) const;
  template <class Recorder>
  std::optional<Hit> walk_whole(const Ray& ray, Recorder& recorder) const;
  /// The triangles the structure was built over, by TriangleId.
  std::span<const Triangle> triangles() const { return m_triangles; }

  const Grid2Info& info() const { return m_info; }
  /// Triangle ids in leaf i, ascending.
  std::span<const TriangleId> leaf(std::uint64_t i) const {
    return {m_refs.data() + m_offsets[i], m_refs.data() + m_offsets[i + 1]};
  }

  /// A cell of any level, as the walk reads it: refined into a sub-grid of
  /// n[0] x n[1] x n[2] cells (`index` its first child's node, the children
  /// contiguous, x fastest); a leaf with a list (`index` its first reference
  /// in m_refs, n[0] its length, or kLongList for a list of 255 or more, whose
  /// end is in m_offsets: the walk reads that only in cells that could not be
  /// refined, whose tests cost far more); or an empty leaf. The top grid's
  /// cells are nodes 0 .. top cells - 1. A list's bounds in its node save the
  /// walk a dependent load per occupied leaf (the offsets' cache miss was an
  /// eighth of a Sponza bounce ray's walk); its leaf number, which only
  /// recorders and long lists read, is in m_leaf_of_node.
  enum Kind : std::uint8_t { list = 0, refined = 1, empty = 2 };
  static constexpr std::uint32_t kLongList = 0xFF;
  struct Node {
    std::uint32_t index = 0;
    std::uint8_t n[3] = {1, 1, 1};
    Kind kind = list;
  };
  static_assert(sizeof(Node) == 8);
  static constexpr std::uint32_t kNoLeaf = 0xFFFFFFFF;

 private:
  template <GridWalk Mode, class Recorder, HitFilter Filter = NoHitFilter>
  bool traverse(const Ray& ray, Hit& best, Recorder& recorder, const Filter& filter = {}) const;
  /// The walk through refined cell `node` (of box `lo`, `size`) from
  /// t_enter on, its leaves at `Level`; true when the whole walk stops.
  template <GridWalk Mode, class Recorder, int Level, class Walk>
  bool walk_sub_grid(const Node& node, const double lo[3], const double size[3], const double inv_size[3],
                     double t_enter, Walk& walk, Recorder& recorder) const;

  std::span<const Triangle> m_triangles;
  Grid2Info m_info;
  Vec3d m_inv_top;  ///< 1 / top cell size per axis
  HugePageVector<Node> m_nodes;
  HugePageVector<std::uint32_t> m_offsets;  ///< leaves + 1 entries into m_refs
  HugePageVector<std::uint32_t> m_leaf_of_node;  ///< a leaf node's leaf number (refined: kNoLeaf)
  HugePageVector<TriangleId> m_refs;
  std::vector<std::uint8_t> m_leaf_level;
  /// Every leaf's box, made on the first cell_box call (reports, cell maps;
  /// never the walk, whose recorders get boxes from it directly).
  mutable std::vector<CellBox> m_leaf_boxes;
  mutable std::once_flag m_boxes_once;
};

}  // namespace kappa
