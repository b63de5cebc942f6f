// Building grid2: the top grid's lists (two parallel passes over the
// triangles, as the uniform grid builds), then, in parallel over top cells,
// each occupied top cell's sub-grid: its resolution from its triangle count,
// its leaves counted, then filled. The top lists are dropped once the leaves
// hold the triangles.
#include <tbb/blocked_range.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include "byte_size.h"
#include "check.h"
#include "grid2.h"
#include "grid_insert.h"
#include "input_error.h"
#include "parallel.h"

namespace kappa {
namespace {

/// A sub-grid's occupancy predicted by eq 19 from its triangles clipped to
/// its top cell (extents and projected areas no larger than the cell's),
/// each grown by the insertion margin m on every side (a cell takes the
/// triangles within m of it: at a coordinate magnitude of 1e6 m is about 4,
/// larger than a small object's cells): what keeps a top cell full of
/// copies of one large triangle, or of triangles smaller than the margin,
/// from exploding, as bounded_resolution keeps the uniform grid.
struct ClippedOccupancy {
  double N = 0;
  Vec3d extent_sum, projected_sum;

  void add(const Triangle& t, const Vec3d& cell, double margin) {
    const Vec3d a(t.v0), b(t.v1), c(t.v2);
    const double m2 = 2 * margin;
    const Vec3d L = max(a, max(b, c)) - min(a, min(b, c)) + Vec3d{m2, m2, m2};
    const Vec3d e = min(L, cell);
    // A projected area grown by the margin: at most its extents' rectangle.
    const Vec3d area = abs(cross(b - a, c - a)) * 0.5;
    const Vec3d grown{area.x + m2 * (L.y + L.z), area.y + m2 * (L.x + L.z), area.z + m2 * (L.x + L.y)};
    N += 1;
    extent_sum = extent_sum + e;
    projected_sum = projected_sum + Vec3d{std::min({grown.x, L.y * L.z, cell.y * cell.z}),
                                          std::min({grown.y, L.x * L.z, cell.x * cell.z}),
                                          std::min({grown.z, L.x * L.y, cell.x * cell.y})};
  }
  double theta_tot(const Vec3d& l) const {
    return N + extent_sum.x / l.x + extent_sum.y / l.y + extent_sum.z / l.z + projected_sum.x / (l.y * l.z) +
           projected_sum.y / (l.x * l.z) + projected_sum.z / (l.x * l.y);
  }
};

/// The sub-grid of a top cell of size `cell` holding `n` triangles: near-cubic
/// cells, leaf_density * n of them, at most kMaxSubAxis per axis, lowered by
/// steps of 2^(1/4) while eq 19 predicts more than kThetaBoundPerTriangle * n
/// + N_c references.
GridResolution sub_resolution(const Vec3d& cell, double n, double leaf_density, const ClippedOccupancy& occupancy) {
  const auto clamped = [](GridResolution r) {
    r.nx = std::min(r.nx, kMaxSubAxis), r.ny = std::min(r.ny, kMaxSubAxis), r.nz = std::min(r.nz, kMaxSubAxis);
    return r;
  };
  double target = std::clamp(leaf_density * n, 1.0, double(kMaxSubAxis) * kMaxSubAxis * kMaxSubAxis);
  GridResolution r = clamped(choose_resolution(cell, target));
  const auto within = [&](const GridResolution& res) {
    const Vec3d l{cell.x / res.nx, cell.y / res.ny, cell.z / res.nz};
    return !(occupancy.theta_tot(l) > kThetaBoundPerTriangle * n + double(res.cells()));
  };
  while (!within(r) && r.cells() > 1) {
    target /= 1.189207115002721;  // 2^(1/4)
    const GridResolution lower = clamped(choose_resolution(cell, std::max(1.0, target)));
    if (lower.cells() < r.cells()) r = lower;
  }
  return r;
}

}  // namespace

GridInfo TwoLevelGrid::sub_grid(std::size_t top_index, const TopCell& top) const {
  const GridInfo& g = m_info.top;
  const std::uint64_t nx = std::uint64_t(g.resolution.nx), ny = std::uint64_t(g.resolution.ny);
  const int ti[3] = {int(top_index % nx), int((top_index / nx) % ny), int(top_index / (nx * ny))};
  GridInfo sub;
  sub.resolution = {top.n[0], top.n[1], top.n[2]};
  sub.margin = g.margin;
  for (int a = 0; a < 3; ++a) {
    const double lo = detail::cell_lo(g, a, ti[a]), hi = detail::cell_hi(g, a, ti[a]);
    // The walk's sub-cells: the top cell's size over n (grid2_traverse.h).
    const double l = g.cell_size[a] / top.n[a];
    (a == 0 ? sub.lo.x : a == 1 ? sub.lo.y : sub.lo.z) = lo;
    (a == 0 ? sub.hi.x : a == 1 ? sub.hi.y : sub.hi.z) = hi;
    (a == 0 ? sub.cell_size.x : a == 1 ? sub.cell_size.y : sub.cell_size.z) = l;
  }
  return sub;
}

TwoLevelGrid::TwoLevelGrid(std::span<const Triangle> triangles, const Grid2Options& options, TaskProgress* progress)
    : m_triangles(triangles) {
  const auto start = std::chrono::steady_clock::now();
  if (triangles.size() >= std::size_t(kNoTriangle)) throw InputError("grid2: more than 2^32 - 1 triangles");
  std::vector<TriangleId> usable_ids;
  usable_ids.reserve(triangles.size());
  for (TriangleId i = 0; i < TriangleId(triangles.size()); ++i)
    if (usable_triangle(triangles[i])) usable_ids.push_back(i);
  m_info.N = usable_ids.size();
  m_info.degenerate = triangles.size() - usable_ids.size();
  GridInfo& g = m_info.top;
  const GridBox box = grid_box(triangles);
  g.lo = box.lo, g.hi = box.hi, g.margin = box.margin;
  const Vec3d extent = g.hi - g.lo;

  // The top grid: top_density * N cells, bounded as the uniform grid's are.
  const double cap = std::min(double(std::numeric_limits<std::uint32_t>::max() - 2), double(options.max_bytes) / 16.0);
  g.resolution = choose_resolution(extent, std::clamp(options.top_density * double(m_info.N), 1.0, std::max(1.0, cap)));
  g.resolution = bounded_resolution(OccupancyModel(triangles), extent, g.resolution);
  const std::uint64_t top_cells = g.resolution.cells();
  for (int a = 0; a < 3; ++a) {
    const double l = extent[a] / g.resolution[a];
    (a == 0 ? g.cell_size.x : a == 1 ? g.cell_size.y : g.cell_size.z) = l;
    (a == 0 ? m_inv_top.x : a == 1 ? m_inv_top.y : m_inv_top.z) = 1.0 / l;
  }
  const std::uint64_t top_bytes = top_cells * sizeof(TopCell);
  if (top_bytes > options.max_bytes)
    throw InputError("grid2: a top grid of " + g.resolution.to_string() + " cells needs " + byte_size(top_bytes) +
                     ", over --grid-max-bytes (" + byte_size(options.max_bytes) + ")");

  // The top grid's lists: count, prefix sum, fill from each cell's end.
  begin_phase(progress, "grid2 " + g.resolution.to_string() + ": top cells", 2 * usable_ids.size());
  std::vector<std::uint64_t> top_offsets(top_cells + 1, 0);
  kappa::parallel_for(tbb::blocked_range<std::size_t>(0, usable_ids.size()), [&](const auto& range) {
    for (std::size_t k = range.begin(); k != range.end(); ++k)
      for_each_overlapped_cell(g, m_inv_top, triangles[usable_ids[k]], [&](std::uint64_t c) {
        std::atomic_ref<std::uint64_t>(top_offsets[c]).fetch_add(1, std::memory_order_relaxed);
      });
    advance(progress, range.size());
  });
  std::uint64_t top_refs = 0;
  for (std::uint64_t c = 0; c < top_cells; ++c) top_offsets[c] = top_refs += top_offsets[c];
  top_offsets[top_cells] = top_refs;
  if (top_bytes + top_refs * sizeof(TriangleId) > options.max_bytes)
    throw InputError("grid2: its top grid " + g.resolution.to_string() + " holds " + std::to_string(top_refs) +
                     " triangle references, over --grid-max-bytes (" + byte_size(options.max_bytes) + ")");
  std::vector<TriangleId> top_lists(top_refs);
  kappa::parallel_for(tbb::blocked_range<std::size_t>(0, usable_ids.size()), [&](const auto& range) {
    for (std::size_t k = range.begin(); k != range.end(); ++k)
      for_each_overlapped_cell(g, m_inv_top, triangles[usable_ids[k]], [&](std::uint64_t c) {
        const std::uint64_t end = std::atomic_ref<std::uint64_t>(top_offsets[c]).fetch_sub(1, std::memory_order_relaxed);
        KAPPA_CHECK_GT(end, 0u);
        top_lists[end - 1] = usable_ids[k];
      });
    advance(progress, range.size());
  });
  // Each top list ascending: the leaves are filled from it in that order.
  kappa::parallel_for(std::uint64_t(0), top_cells, [&](std::uint64_t c) {
    std::sort(top_lists.begin() + std::ptrdiff_t(top_offsets[c]), top_lists.begin() + std::ptrdiff_t(top_offsets[c + 1]));
  });

  // Sub-grid resolutions, then where each top cell's leaves start.
  m_top.assign(top_cells, TopCell{});
  kappa::parallel_for(std::uint64_t(0), top_cells, [&](std::uint64_t c) {
    const std::uint64_t n = top_offsets[c + 1] - top_offsets[c];
    if (n == 0) return;
    const GridInfo whole = sub_grid(c, TopCell{});
    const Vec3d cell = whole.hi - whole.lo;
    ClippedOccupancy occupancy;
    for (std::uint64_t k = top_offsets[c]; k < top_offsets[c + 1]; ++k) occupancy.add(triangles[top_lists[k]], cell, g.margin);
    const GridResolution r = sub_resolution(cell, double(n), options.leaf_density, occupancy);
    m_top[c].n[0] = std::uint8_t(r.nx), m_top[c].n[1] = std::uint8_t(r.ny), m_top[c].n[2] = std::uint8_t(r.nz);
    m_top[c].occupied = 1;
  });
  std::uint64_t leaves = 0;
  for (std::uint64_t c = 0; c < top_cells; ++c) {
    if (leaves >= std::numeric_limits<std::uint32_t>::max()) break;
    m_top[c].first_leaf = std::uint32_t(leaves);
    leaves += std::uint64_t(m_top[c].n[0]) * m_top[c].n[1] * m_top[c].n[2];
    m_info.top_occupied += m_top[c].occupied;
  }
  const std::uint64_t offset_bytes = (leaves + 1) * sizeof(std::uint32_t);
  if (leaves >= std::numeric_limits<std::uint32_t>::max() || top_bytes + offset_bytes > options.max_bytes)
    throw InputError("grid2: " + std::to_string(leaves) + " leaves need " + byte_size(top_bytes + offset_bytes) +
                     " for offsets alone, over --grid-max-bytes (" + byte_size(options.max_bytes) +
                     ") or 2^32 - 1 leaves");
  m_info.leaves = leaves;

  // Leaves counted: each top cell's triangles into its sub-grid (one task a
  // top cell, so no atomics).
  begin_phase(progress, "grid2 " + g.resolution.to_string() + ": sub-grids", 2 * top_cells);
  m_offsets.assign(leaves + 1, 0);
  const auto for_each_leaf_of = [&](std::uint64_t c, auto&& f, bool descending) {
    const GridInfo sub = sub_grid(c, m_top[c]);
    const Vec3d inv{1.0 / sub.cell_size.x, 1.0 / sub.cell_size.y, 1.0 / sub.cell_size.z};
    const std::uint64_t first = top_offsets[c], end = top_offsets[c + 1];
    for (std::uint64_t k = 0; k < end - first; ++k) {
      const TriangleId id = top_lists[descending ? end - 1 - k : first + k];
      for_each_overlapped_cell(sub, inv, triangles[id], [&](std::uint64_t leaf) { f(m_top[c].first_leaf + leaf, id); });
    }
  };
  kappa::parallel_for(tbb::blocked_range<std::uint64_t>(0, top_cells), [&](const auto& range) {
    for (std::uint64_t c = range.begin(); c != range.end(); ++c)
      if (m_top[c].occupied) for_each_leaf_of(c, [&](std::uint64_t leaf, TriangleId) { ++m_offsets[leaf]; }, false);
    advance(progress, range.size());
  });
  // Inclusive prefix sum: each leaf's end, counted down to its start while filling.
  std::uint64_t total = 0;
  for (std::uint64_t i = 0; i < leaves; ++i) {
    const std::uint32_t n = m_offsets[i];
    m_info.max_occupancy = std::max(m_info.max_occupancy, n);
    m_info.empty_leaves += n == 0;
    total += n;
    m_offsets[i] = std::uint32_t(std::min<std::uint64_t>(total, std::numeric_limits<std::uint32_t>::max()));
  }
  const std::uint64_t bytes = top_bytes + offset_bytes + total * sizeof(TriangleId);
  if (total >= std::numeric_limits<std::uint32_t>::max() || bytes > options.max_bytes)
    throw InputError("grid2: its leaves hold " + std::to_string(total) + " triangle references (" + byte_size(bytes) +
                     "), over --grid-max-bytes (" + byte_size(options.max_bytes) + ") or 2^32 - 1 references");
  m_offsets[leaves] = std::uint32_t(total);
  m_refs.resize(total);
  // Filled from each top list's end down, so every leaf's list ends ascending.
  kappa::parallel_for(tbb::blocked_range<std::uint64_t>(0, top_cells), [&](const auto& range) {
    for (std::uint64_t c = range.begin(); c != range.end(); ++c)
      if (m_top[c].occupied)
        for_each_leaf_of(c, [&](std::uint64_t leaf, TriangleId id) {
          KAPPA_CHECK_GT(m_offsets[leaf], 0u);
          m_refs[--m_offsets[leaf]] = id;
        }, true);
    advance(progress, range.size());
  });
  KAPPA_CHECK_EQ(m_offsets[0], 0u);
  m_info.theta_tot = total;
  m_info.bytes = bytes;

  // Per level: level 0 the empty top cells (their records and offsets),
  // level 1 the sub-grids' leaves with their references.
  m_info.levels[0] = {0, top_cells - m_info.top_occupied, 0,
                      (top_cells - m_info.top_occupied) * (sizeof(TopCell) + sizeof(std::uint32_t))};
  m_info.levels[1] = {1, leaves - m_info.levels[0].N_c, total, bytes - m_info.levels[0].bytes};
  m_info.build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace kappa
