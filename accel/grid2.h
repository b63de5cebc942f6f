// grid2: the two-level grid (Kalojanov, Billeter & Slusallek, "Two-Level
// Grids for Ray Tracing on GPUs", EG 2011), exact like the uniform grid. A
// coarse top grid over the scene; each top cell that holds triangles is its
// own uniform sub-grid, sized by its triangle count, so that a small detailed
// object in a large box gets fine cells where its triangles are while empty
// space is crossed one top cell at a time.
//
// The leaves are what statistics call cells: an empty top cell is one leaf
// of level 0, every cell of a sub-grid a leaf of level 1. The leaves tile the
// box without overlap, so a ray's walk visits each leaf it crosses once, in
// order along the ray, and eq 8's kappa reads them as it reads a uniform
// grid's cells (stats/README.md, "grid2").
//
// Exactness follows the uniform grid's argument (grid.h): every leaf is a
// closed box inflated by the same insertion margin, a closest-hit walk stops
// only after the leaf whose exit lies beyond the hit by that margin, and the
// triangle test is the one shared function.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "accel.h"
#include "cell_layout.h"
#include "grid.h"
#include "grid_resolution.h"
#include "huge_pages.h"
#include "task_progress.h"

namespace kappa {

/// Default top density: top cells per triangle. Measured with `kappa bench
/// --accel grid2` over top densities 1/64 .. 1 and leaf densities 1 .. 32 on
/// the shared scenes (the closing note of the grid2 issue gives the table).
inline constexpr double kDefaultGrid2TopDensity = 1.0 / 8.0;
/// Default leaf density: sub-grid cells per triangle of their top cell.
inline constexpr double kDefaultGrid2LeafDensity = 4.0;
/// A sub-grid's most cells per axis (its resolution is stored in bytes).
inline constexpr int kMaxSubAxis = 255;

struct Grid2Options {
  double top_density = kDefaultGrid2TopDensity;
  double leaf_density = kDefaultGrid2LeafDensity;
  std::uint64_t max_bytes = default_grid_max_bytes();
};

/// One level of grid2, for reports: its leaves, their total occupancy and
/// the bytes that level adds.
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
  std::uint64_t top_occupied = 0;  ///< top cells holding triangles (each a sub-grid)
  std::uint64_t leaves = 0;   ///< N_c: empty top cells plus every sub-grid cell
  std::uint64_t theta_tot = 0;     ///< references over all leaves
  std::uint32_t max_occupancy = 0;
  std::uint64_t empty_leaves = 0;
  std::uint64_t bytes = 0;
  double build_s = 0;
  Grid2Level levels[2];
};

class TwoLevelGrid final : public Accelerator, public CellLayout {
 public:
  /// Throws InputError if the structure would exceed options.max_bytes or
  /// 2^32 - 1 leaves or references.
  TwoLevelGrid(std::span<const Triangle> triangles, const Grid2Options& options, TaskProgress* progress = nullptr);

  std::optional<Hit> closest_hit(const Ray& ray) const override;
  bool any_hit(const Ray& ray) const override;
  std::string_view name() const override { return "grid2"; }
  AccelKind kind() const override { return AccelKind::grid2; }
  std::uint64_t bytes() const override { return m_info.bytes; }
  double build_s() const override { return m_info.build_s; }
  /// The report's "grid2" section (stats/README.md).
  nlohmann::ordered_json report_section() const override;
  const CellLayout* cells() const override { return this; }

  // CellLayout: the leaves, top cell by top cell (x fastest, then y, then
  // z), each sub-grid's leaves x fastest within it.
  std::uint64_t cell_count() const override { return m_info.leaves; }
  std::vector<std::uint32_t> occupancies() const override;
  CellBox cell_box(std::uint64_t i) const override;
  int cell_level(std::uint64_t i) const override;
  CellBox bounds() const override { return {m_info.top.lo, m_info.top.hi}; }
  std::optional<Vec3d> uniform_cell_size() const override { return std::nullopt; }
  std::string resolution_text() const override;
  std::vector<Level> levels() const override {
    return {{0, m_info.levels[0].N_c, m_info.levels[0].theta_tot}, {1, m_info.levels[1].N_c, m_info.levels[1].theta_tot}};
  }

  /// The queries with a recorder (accel/recorder.h; the walk is in grid2_traverse.h).
  template <class Recorder>
  std::optional<Hit> closest_hit(const Ray& ray, Recorder& recorder) const;
  template <class Recorder>
  bool any_hit(const Ray& ray, Recorder& recorder) const;
  template <class Recorder>
  std::optional<Hit> walk_whole(const Ray& ray, Recorder& recorder) const;

  const Grid2Info& info() const { return m_info; }
  /// Triangle ids in leaf i, ascending.
  std::span<const TriangleId> leaf(std::uint64_t i) const {
    return {m_refs.data() + m_offsets[i], m_refs.data() + m_offsets[i + 1]};
  }

  /// A top cell: where its leaves start and its sub-grid's resolution
  /// (1x1x1 and one empty leaf for an empty top cell).
  struct TopCell {
    std::uint32_t first_leaf = 0;
    std::uint8_t n[3] = {1, 1, 1};
    std::uint8_t occupied = 0;
  };

 private:
  template <GridWalk Mode, class Recorder>
  bool traverse(const Ray& ray, Hit& best, Recorder& recorder) const;
  /// The top cell holding leaf i.
  std::uint64_t top_of_leaf(std::uint64_t i) const;
  /// Top cell (ix, iy, iz)'s box: the uniform grid's cell planes.
  CellBox top_box(int ix, int iy, int iz) const;
  /// Top cell `top_index`'s sub-grid as a GridInfo (box, cells, margin), the
  /// cells the walk steps through: what insertion and cell boxes use.
  GridInfo sub_grid(std::size_t top_index, const TopCell& top) const;

  std::span<const Triangle> m_triangles;
  Grid2Info m_info;
  Vec3d m_inv_top;  ///< 1 / top cell size per axis
  HugePageVector<TopCell> m_top;
  HugePageVector<std::uint32_t> m_offsets;  ///< leaves + 1 entries into m_refs
  HugePageVector<TriangleId> m_refs;
};

}  // namespace kappa
