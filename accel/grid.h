// The uniform grid (seed paper, sections 2-7): cells over the scene's bounding
// box, each holding the triangles that overlap it, walked by a 3D-DDA
// (Amanatides & Woo 1987). Returns bitwise the same closest hit as naive.
//
// Cells are closed boxes, inflated by kCellMargin (a few float ulps of the
// scene's coordinates) for insertion: a triangle touching a cell, or lying
// within rounding distance of it, is in it. That is what makes the walk
// agree with naive even for rays in cell planes, through grid edges and
// vertices, and for walls lying on the bounding box. The occupancy Theta_i of a
// cell is counted the same way.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "accel.h"
#include "grid_resolution.h"

namespace kappa {

/// Default lambda in N_c = lambda * N, measured with tools/grid_density_sweep.sh
/// on the Cornell box, both bunnies, Sponza and the teapot in a stadium: 32
/// keeps every scene within about 15 % of its own best density except the
/// teapot (where no uniform density is good), while architecture (Sponza) is
/// best near 8-16 and models on a wide ground plane (bunny) near 64-128.
inline constexpr double kDefaultGridDensity = 32.0;

/// Insertion margin of every cell, in float ulps of the scene's coordinate
/// magnitude (max |coordinate| + diagonal): well above the rounding of the
/// float triangle test and of the double DDA.
inline constexpr double kMarginUlps = 32.0;

/// A quarter of physical memory: the default --grid-max-bytes.
std::uint64_t default_grid_max_bytes();

struct GridOptions {
  std::optional<GridResolution> resolution;  ///< nullopt = auto from density
  double density = kDefaultGridDensity;
  std::uint64_t max_bytes = default_grid_max_bytes();
  /// Cells over this box instead of the scene's bounds (e.g. a grid shifted
  /// by a random offset, to average occupancy over placements); it must hold
  /// the triangles that should be in the grid.
  std::optional<std::pair<Vec3d, Vec3d>> box;
};

/// What the grid measured about itself while building (for reports).
struct GridInfo {
  GridResolution resolution;
  Vec3d lo, hi;           ///< the (inflated) box the cells tile
  Vec3d cell_size;        ///< l_x, l_y, l_z (scene units)
  double margin = 0;      ///< insertion inflation of every cell (scene units)
  std::uint64_t N = 0;    ///< triangles in the grid
  std::uint64_t degenerate = 0;  ///< zero-area or non-finite triangles left out
  std::uint64_t theta_tot = 0;   ///< total occupancy = total multiplicity M (eq 13)
  std::uint32_t max_occupancy = 0;  ///< largest Theta_i
  std::uint64_t empty_cells = 0;
  std::uint64_t bytes = 0;  ///< cell offsets + triangle index array + occupancy bits
  double build_s = 0;
};

/// How far a walk goes: to the closest hit, to any hit, or along the whole
/// chord (the paper's lines and segments, for statistics).
enum class GridWalk { closest, any, whole };

/// What one walk did, counted in registers and handed to the recorder once
/// at the end.
struct WalkCounts {
  std::uint64_t cells = 0;  ///< cells visited
  std::uint64_t refs = 0;   ///< sum of Theta_i over them (before mailboxing)
  std::uint64_t tests = 0;  ///< triangle tests made
  std::uint64_t skips = 0;  ///< tests the mailbox avoided
  /// The model's cells for the walked segment, 1 + sum_a |d_a| len / l_a
  /// (seed paper eq 24 per axis) less 1/2 for each end on the grid box, over
  /// the part of [tmin, end] inside the grid, where end is the closest hit
  /// for closest-hit walks and tmax otherwise (an any-hit walk's stop is not
  /// known: an upper bound); 0 if that part is empty.
  double predicted_cells = 0;
};


class UniformGrid final : public Accelerator {
 public:
  /// Throws std::invalid_argument if the grid would exceed options.max_bytes
  /// or 2^32 - 1 cells or references.
  UniformGrid(std::span<const Triangle> triangles, const GridOptions& options);

  std::optional<Hit> closest_hit(const Ray& ray) const override;
  bool any_hit(const Ray& ray) const override;
  std::string_view name() const override { return "grid"; }

  /// The same queries, reporting each visited cell, triangle test, mailbox
  /// skip and hit to `recorder` (see grid_traverse.h, stats/counters.h).
  template <class Recorder>
  std::optional<Hit> closest_hit(const Ray& ray, Recorder& recorder) const;
  template <class Recorder>
  bool any_hit(const Ray& ray, Recorder& recorder) const;
  /// Walks every cell of the ray's [tmin, tmax] inside the grid, testing
  /// every triangle met (no stop at a hit); returns the closest hit.
  template <class Recorder>
  std::optional<Hit> walk_whole(const Ray& ray, Recorder& recorder) const;

  const GridInfo& info() const { return m_info; }
  std::uint64_t cell_index(int ix, int iy, int iz) const {
    return std::uint64_t(ix) + std::uint64_t(m_info.resolution.nx) *
                                   (std::uint64_t(iy) + std::uint64_t(m_info.resolution.ny) * std::uint64_t(iz));
  }
  /// Triangle ids in a cell, ascending.
  std::span<const TriangleId> cell(std::uint64_t index) const {
    return {m_refs.data() + m_offsets[index], m_refs.data() + m_offsets[index + 1]};
  }

 private:
  template <GridWalk Mode, class Recorder>
  bool traverse(const Ray& ray, Hit& best, Recorder& recorder) const;

  std::span<const Triangle> m_triangles;
  GridInfo m_info;
  Vec3d m_inv_cell;                 ///< 1 / cell size per axis
  std::vector<std::uint32_t> m_offsets;  ///< N_c + 1 entries into m_refs
  std::vector<TriangleId> m_refs;       ///< triangle ids, cell by cell
  /// One bit per cell, set if it holds any triangle: 1/32 of the offsets'
  /// size, so it stays in cache and empty cells cost no offset loads.
  std::vector<std::uint64_t> m_occupied;
};

}  // namespace kappa
