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
#include <functional>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "accel.h"
#include "cell_layout.h"
#include "core/huge_pages.h"
#include "core/task_progress.h"
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

/// The box a grid over `triangles` tiles: the usable triangles' bounds
/// inflated by the insertion margin (kMarginUlps of the coordinates'
/// magnitude), and that margin. What a resolution chooser needs to know the
/// cells a resolution gives before building.
struct GridBox {
  Vec3d lo, hi;
  double margin = 0;
  Vec3d extent() const { return hi - lo; }
};
GridBox grid_box(std::span<const Triangle> triangles);

/// Theta_tot predicted by eq 19 (stats/cost_model.h) for cells of side `cell`,
/// from sums over the triangles made once: eq 19 is linear in each
/// triangle's extents and projected areas, so a chooser trying many
/// resolutions pays O(N) once and O(1) per resolution.
struct OccupancyModel {
  double N = 0;          ///< usable triangles
  Vec3d extent_sum;      ///< sum over triangles of their extent along each axis
  Vec3d projected_sum;   ///< sum of their projected areas onto the planes normal to x, y, z
  explicit OccupancyModel(std::span<const Triangle> triangles);
  double theta_tot(const Vec3d& cell) const;
};

/// The rule that keeps a grid from exploding (10^4 copies of one large
/// triangle, each in most cells): a resolution whose eq 19 Theta_tot exceeds
/// kThetaBoundPerTriangle * N + N_c is lowered, for `auto` and the cost
/// model's chooser alike, before anything is allocated. Real scenes stay far
/// below (Theta_tot / N is 1.5 to 5 at lambda = 32 on ../shared/scenes).
inline constexpr double kThetaBoundPerTriangle = 16.0;

/// The ids of the triangles a grid holds (usable_triangle: finite, of
/// non-zero area), ascending.
std::vector<TriangleId> usable_triangle_ids(std::span<const Triangle> triangles);

/// The resolution --grid-res auto gives: density * N near-cubic cells over
/// `extent`, never more than 32-bit offsets or max_bytes allow (4 bytes a
/// cell, and room for as many again of references), then bounded_resolution.
/// The uniform grid's, and grid2's top grid.
GridResolution density_resolution(const OccupancyModel& occupancy, const Vec3d& extent, double density, double N,
                                  std::uint64_t max_bytes);

/// The most cells at or below `resolution`'s (near-cubic, by
/// choose_resolution over `extent`) whose predicted Theta_tot keeps within the
/// bound; `resolution` itself when it does.
GridResolution bounded_resolution(const OccupancyModel& occupancy, const Vec3d& extent, GridResolution resolution);

class UniformGrid;

struct GridOptions {
  std::optional<GridResolution> resolution;  ///< nullopt = auto from density
  double density = kDefaultGridDensity;
  std::uint64_t max_bytes = default_grid_max_bytes();
  /// Cells over this box instead of the scene's bounds (e.g. a grid shifted
  /// by a random offset, to average occupancy over placements); it must hold
  /// the triangles that should be in the grid.
  std::optional<std::pair<Vec3d, Vec3d>> box;
  /// Lists for some cells only, the rest left empty: called with the grid
  /// before any triangle is in it (every cell empty, the walk already the
  /// whole grid's), it returns the cells to fill as a bitset of N_c bits.
  /// A resolution chooser's candidate fills the cells its pilot's walks
  /// visit, so that it counts them as the whole grid would at a fraction of
  /// the build (GridInfo::partial; its theta_tot and bytes are its own).
  std::function<std::vector<std::uint64_t>(const UniformGrid&)> cells_to_fill;
  /// Eq 19's sums over these same triangles, when the caller has made them
  /// (a chooser predicting from them too), so that an auto resolution does
  /// not make them again; nullptr: made here. Must outlive the constructor.
  const OccupancyModel* occupancy = nullptr;
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
  std::uint32_t max_occupancy = 0;  ///< largest Theta_i (the report's theta_max)
  std::uint64_t max_multiplicity = 0;  ///< the most cells any one triangle is in (largest M_j, eq 13)
  std::uint64_t empty_cells = 0;
  std::uint64_t bytes = 0;  ///< cell offsets + triangle index array + occupancy bits (a partial grid: what it holds)
  double build_s = 0;
  bool partial = false;     ///< built with GridOptions::cells_to_fill: only some cells' lists
};

class UniformGrid final : public Accelerator, public CellLayout {
 public:
  /// Throws InputError if the grid would exceed options.max_bytes
  /// or 2^32 - 1 cells or references.
  /// Reports its passes to `progress`, if given.
  UniformGrid(std::span<const Triangle> triangles, const GridOptions& options, TaskProgress* progress = nullptr);

  std::optional<Hit> closest_hit(const Ray& ray) const override;
  bool any_hit(const Ray& ray) const override;
  std::optional<Hit> closest_hit(const Ray& ray, const FunctionHitFilter& filter) const override;
  bool any_hit(const Ray& ray, const FunctionHitFilter& filter) const override;
  std::string_view name() const override { return "grid"; }
  AccelKind kind() const override { return AccelKind::grid; }
  std::uint64_t bytes() const override { return m_info.bytes; }
  std::uint64_t reference_bytes() const override { return m_info.theta_tot * sizeof(TriangleId); }
  double build_s() const override { return m_info.build_s; }
  /// The report's "grid" section: res, N_c, N, cell_size, build_s, bytes,
  /// theta_tot, theta_avg, theta_max, max_multiplicity, empty_fraction, degenerate.
  nlohmann::ordered_json report_section() const override;
  const CellLayout* cells() const override { return this; }

  // CellLayout: one level of equal cells, indexed x fastest, then y, then z.
  std::uint64_t cell_count() const override { return m_info.resolution.cells(); }
  std::vector<std::uint32_t> occupancies() const override;
  CellBox cell_box(std::uint64_t i) const override;
  int cell_level(std::uint64_t) const override { return 0; }
  CellBox bounds() const override { return {m_info.lo, m_info.hi}; }
  std::optional<Vec3d> uniform_cell_size() const override { return m_info.cell_size; }
  std::string resolution_text() const override { return m_info.resolution.to_string(); }

  /// The same queries, reporting what the walk does to `recorder` (the
  /// protocol of recorder.h; the walk is in grid_traverse.h).
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
  /// The triangles the grid was built over, by TriangleId.
  std::span<const Triangle> triangles() const { return m_triangles; }
  /// Walks every cell of the ray's [tmin, tmax] inside the grid, testing
  /// every triangle met (no stop at a hit); returns the closest hit.
  template <class Recorder>
  std::optional<Hit> walk_whole(const Ray& ray, Recorder& recorder) const;
  /// The cells, lists and (mailboxed) tests a closest-hit walk of `ray`
  /// makes, reported to `recorder` as that walk reports them, when its hit
  /// is known (`t_hit`, from another exact accelerator; nullopt for a miss):
  /// no triangle is tested. What a resolution chooser counts on a
  /// candidate grid from a pilot's rays.
  template <class Recorder>
  void count_closest_walk(const Ray& ray, std::optional<float> t_hit, Recorder& recorder) const;

  const GridInfo& info() const { return m_info; }
  std::uint64_t cell_index(int ix, int iy, int iz) const {
    return std::uint64_t(ix) + std::uint64_t(m_info.resolution.nx) *
                                   (std::uint64_t(iy) + std::uint64_t(m_info.resolution.ny) * std::uint64_t(iz));
  }
  /// Triangle ids in a cell, ascending (none in a cell a partial grid did
  /// not fill).
  std::span<const TriangleId> cell(std::uint64_t index) const {
    if (m_info.partial && !filled(index)) return {};
    const std::size_t s = slot(index);
    return {m_refs.data() + m_offsets[s], m_refs.data() + m_offsets[s + 1]};
  }

 private:
  template <GridWalk Mode, class Recorder, bool TestTriangles = true, HitFilter Filter = NoHitFilter>
  bool traverse(const Ray& ray, Hit& best, Recorder& recorder, const Filter& filter = {}) const;

  std::span<const Triangle> m_triangles;
  GridInfo m_info;
  Vec3d m_inv_cell;                 ///< 1 / cell size per axis
  /// A cell's entry in m_offsets: the cell itself, or in a partial grid its
  /// rank among the filled cells (whose offsets alone it stores: a counting
  /// grid of the dragon at lambda = 32 spent 0.28 s of its 0.55 s faulting in
  /// 112 MB of offsets for the 4 % of cells the pilot visits).
  std::size_t slot(std::uint64_t c) const {
    if (m_filled.empty()) return std::size_t(c);
    const std::uint64_t below = m_filled[c >> 6] & ((std::uint64_t(1) << (c & 63)) - 1);
    return std::size_t(m_filled_rank[c >> 6]) + std::size_t(__builtin_popcountll(below));
  }
  bool filled(std::uint64_t c) const { return (m_filled[c >> 6] >> (c & 63)) & 1; }

  HugePageVector<std::uint32_t> m_offsets;  ///< N_c + 1 entries into m_refs (a partial grid: filled cells + 1)
  HugePageVector<TriangleId> m_refs;       ///< triangle ids, cell by cell
  /// One bit per cell, set if it holds any triangle: 1/32 of the offsets'
  /// size, so it stays in cache and empty cells cost no offset loads.
  HugePageVector<std::uint64_t> m_occupied;
  /// A partial grid's filled cells, one bit per cell, and the filled cells
  /// before each 64-bit word of them; empty in a whole grid.
  std::vector<std::uint64_t> m_filled;
  std::vector<std::uint32_t> m_filled_rank;
};

}  // namespace kappa
