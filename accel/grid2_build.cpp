// Building grid2: the top grid's lists (two parallel passes over the
// triangles, as the uniform grid builds), then, in parallel over top cells,
// each top cell's tree: a cell holding more than kGrid2LeafTriangles
// triangles becomes a sub-grid sized by its count, its cells' lists made
// from its own, and so on down to kMaxGrid2Levels levels. The trees are then
// laid out one after another: nodes, leaf offsets, references.
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/byte_size.h"
#include "core/check.h"
#include "core/input_error.h"
#include "core/parallel.h"
#include "grid2.h"
#include "grid_insert.h"

namespace kappa {
namespace {

using Node = NestedGrid::Node;

/// A sub-grid's occupancy predicted by eq 19 from its triangles clipped to
/// the cell it refines (extents and projected areas no larger than the
/// cell's), each grown by the insertion margin m on every side (a cell takes
/// the triangles within m of it: at a coordinate magnitude of 1e6 m is about
/// 4, larger than a small object's cells): what keeps a cell full of copies
/// of one large triangle, or of triangles smaller than the margin, from
/// exploding, as bounded_resolution keeps the uniform grid.
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

/// The sub-grid of a cell of size `cell` holding `n` triangles: near-cubic
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

/// One top cell's tree, built by one task: nodes (the root first, each
/// refined node's children contiguous), and its leaves' lists in leaf order.
/// Indices are local; layout() makes them global.
struct LocalTree {
  /// A top cell that stays one leaf (most of them): nothing below, its list
  /// is its top list, and none of the vectors is allocated.
  bool top_leaf = false;
  std::vector<Node> nodes;
  std::vector<std::uint32_t> leaf_sizes;
  std::vector<std::uint8_t> leaf_levels;
  std::vector<TriangleId> refs;
  std::uint64_t refined[kMaxGrid2Levels] = {};  ///< refined cells per level
};

/// A cell's box for insertion and its size as the walk steps it: the walk's
/// cells of a sub-grid are its cell's size over n, from its low corner.
struct CellFrame {
  Vec3d lo, hi, size;
};

/// A build task's working memory, kept across the top cells it builds so
/// that a cell's sub-grid costs no allocation once the buffers have grown:
/// the (child, id) pairs of the cell being split, and per level the lists
/// of its children while they are built.
struct BuildScratch {
  struct Level {
    std::vector<std::uint32_t> offsets, cursor;
    std::vector<TriangleId> lists;
  };
  std::vector<std::pair<std::uint32_t, TriangleId>> pairs;
  Level level[kMaxGrid2Levels];
};

class TreeBuilder {
 public:
  TreeBuilder(std::span<const Triangle> triangles, double margin, double leaf_density, LocalTree& tree,
              BuildScratch& scratch)
      : m_triangles(triangles), m_margin(margin), m_leaf_density(leaf_density), m_tree(tree), m_scratch(scratch),
        m_pairs(scratch.pairs) {}

  /// Fills node `index` (already in the tree) for a cell holding `ids`
  /// (ascending), at `level`.
  void build(std::size_t index, const CellFrame& cell, std::span<const TriangleId> ids, int level) {
    if (ids.size() <= kGrid2LeafTriangles || level + 1 >= kMaxGrid2Levels) return make_leaf(index, ids, level);
    ClippedOccupancy occupancy;
    const Vec3d extent = cell.hi - cell.lo;
    for (TriangleId id : ids) occupancy.add(m_triangles[id], extent, m_margin);
    const GridResolution r = sub_resolution(extent, double(ids.size()), m_leaf_density, occupancy);
    if (r.cells() == 1) return make_leaf(index, ids, level);
    // Refining pays only if a ray meets fewer triangles in a sub-grid cell
    // than in the cell: not for triangles that each span the cell (copies of
    // one large triangle, a wall), where every level would multiply the
    // references. Eq 19 must predict at most half the cell's triangles per
    // sub-grid cell on average.
    const Vec3d l{extent.x / r.nx, extent.y / r.ny, extent.z / r.nz};
    if (occupancy.theta_tot(l) > 0.5 * double(ids.size()) * double(r.cells())) return make_leaf(index, ids, level);

    GridInfo sub;
    sub.resolution = r;
    sub.margin = m_margin;
    sub.lo = cell.lo, sub.hi = cell.hi;
    sub.cell_size = Vec3d{sub_cell_size(cell.size.x, r.nx), sub_cell_size(cell.size.y, r.ny), sub_cell_size(cell.size.z, r.nz)};
    const Vec3d inv{1.0 / sub.cell_size.x, 1.0 / sub.cell_size.y, 1.0 / sub.cell_size.z};
    // The children's lists: one overlap pass into (child, id) pairs, in id
    // order, then a counting sort by child (each list ascending).
    const std::uint64_t children = r.cells();
    m_pairs.clear();
    for (TriangleId id : ids)
      for_each_overlapped_cell(sub, inv, m_triangles[id],
                               [&](std::uint64_t c) { m_pairs.push_back({std::uint32_t(c), id}); });
    // The lists live in this level's scratch until the children are built
    // (a child's build fills the next level's), reused by its siblings.
    BuildScratch::Level& scratch = m_scratch.level[level];
    std::vector<std::uint32_t>& offsets = scratch.offsets;
    offsets.assign(children + 1, 0);
    for (const auto& [c, id] : m_pairs) ++offsets[c + 1];
    for (std::uint64_t c = 0; c < children; ++c) offsets[c + 1] += offsets[c];
    std::vector<TriangleId>& lists = scratch.lists;
    lists.resize(offsets[children]);
    scratch.cursor.assign(offsets.begin(), offsets.end() - 1);
    for (const auto& [c, id] : m_pairs) lists[scratch.cursor[c]++] = id;

    const std::size_t first = m_tree.nodes.size();
    m_tree.nodes.resize(first + children);
    Node& node = m_tree.nodes[index];
    node.kind = NestedGrid::refined;
    node.index = std::uint32_t(first);
    node.n[0] = std::uint8_t(r.nx), node.n[1] = std::uint8_t(r.ny), node.n[2] = std::uint8_t(r.nz);
    ++m_tree.refined[level];
    std::uint64_t c = 0;
    for (int z = 0; z < r.nz; ++z)
      for (int y = 0; y < r.ny; ++y)
        for (int x = 0; x < r.nx; ++x, ++c) {
          const int k[3] = {x, y, z};
          CellFrame child;
          for (int a = 0; a < 3; ++a) {
            (a == 0 ? child.lo.x : a == 1 ? child.lo.y : child.lo.z) = detail::cell_lo(sub, a, k[a]);
            (a == 0 ? child.hi.x : a == 1 ? child.hi.y : child.hi.z) = detail::cell_hi(sub, a, k[a]);
          }
          child.size = sub.cell_size;
          build(first + c, child, std::span(lists).subspan(offsets[c], offsets[c + 1] - offsets[c]), level + 1);
        }
  }

 private:
  void make_leaf(std::size_t index, std::span<const TriangleId> ids, int level) {
    Node& node = m_tree.nodes[index];
    node.kind = ids.empty() ? NestedGrid::empty : NestedGrid::list;
    node.index = std::uint32_t(m_tree.leaf_sizes.size());
    m_tree.leaf_sizes.push_back(std::uint32_t(ids.size()));
    m_tree.leaf_levels.push_back(std::uint8_t(level));
    m_tree.refs.insert(m_tree.refs.end(), ids.begin(), ids.end());
  }

  std::span<const Triangle> m_triangles;
  double m_margin, m_leaf_density;
  LocalTree& m_tree;
  BuildScratch& m_scratch;
  std::vector<std::pair<std::uint32_t, TriangleId>>& m_pairs;  ///< consumed before the recursion
};

}  // namespace

NestedGrid::NestedGrid(std::span<const Triangle> triangles, const Grid2Options& options, TaskProgress* progress)
    : m_triangles(triangles) {
  const auto start = std::chrono::steady_clock::now();
  if (triangles.size() >= std::size_t(kNoTriangle)) throw InputError("grid2: more than 2^32 - 1 triangles");
  const std::vector<TriangleId> usable_ids = usable_triangle_ids(triangles);
  m_info.N = usable_ids.size();
  m_info.degenerate = triangles.size() - usable_ids.size();
  GridInfo& g = m_info.top;
  const GridBox box = grid_box(triangles);
  g.lo = box.lo, g.hi = box.hi, g.margin = box.margin;
  const Vec3d extent = g.hi - g.lo;

  // The top grid: top_density * N cells, bounded as the uniform grid's are.
  g.resolution =
      density_resolution(OccupancyModel(triangles), extent, options.top_density, double(m_info.N), options.max_bytes);
  const std::uint64_t top_cells = g.resolution.cells();
  for (int a = 0; a < 3; ++a) {
    const double l = extent[a] / g.resolution[a];
    (a == 0 ? g.cell_size.x : a == 1 ? g.cell_size.y : g.cell_size.z) = l;
    (a == 0 ? m_inv_top.x : a == 1 ? m_inv_top.y : m_inv_top.z) = 1.0 / l;
  }
  // A top cell's node, its leaf number and (as a leaf) its offset.
  const std::uint64_t top_bytes = top_cells * (sizeof(Node) + 2 * sizeof(std::uint32_t));
  if (top_bytes > options.max_bytes)
    throw InputError("grid2: a top grid of " + g.resolution.to_string() + " cells needs " + byte_size(top_bytes) +
                     ", over --grid-max-bytes (" + byte_size(options.max_bytes) + ")");

  // The top grid's lists: count, prefix sum, fill from each cell's end, sort.
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

  // Each top cell's tree, in parallel (one task a top cell).
  begin_phase(progress, "grid2 " + g.resolution.to_string() + ": sub-grids", top_cells);
  std::vector<LocalTree> trees(top_cells);
  tbb::enumerable_thread_specific<BuildScratch> scratch;
  const std::uint64_t nx = std::uint64_t(g.resolution.nx), ny = std::uint64_t(g.resolution.ny);
  kappa::parallel_for(tbb::blocked_range<std::uint64_t>(0, top_cells), [&](const auto& range) {
    for (std::uint64_t c = range.begin(); c != range.end(); ++c) {
      const auto ids = std::span(top_lists).subspan(top_offsets[c], top_offsets[c + 1] - top_offsets[c]);
      std::sort(ids.begin(), ids.end());
      const int k[3] = {int(c % nx), int((c / nx) % ny), int(c / (nx * ny))};
      CellFrame cell;
      for (int a = 0; a < 3; ++a) {
        (a == 0 ? cell.lo.x : a == 1 ? cell.lo.y : cell.lo.z) = detail::cell_lo(g, a, k[a]);
        (a == 0 ? cell.hi.x : a == 1 ? cell.hi.y : cell.hi.z) = detail::cell_hi(g, a, k[a]);
      }
      cell.size = g.cell_size;
      LocalTree& tree = trees[c];
      if (ids.size() <= kGrid2LeafTriangles) {
        tree.top_leaf = true;
        continue;
      }
      tree.nodes.resize(1);
      TreeBuilder(triangles, g.margin, options.leaf_density, tree, scratch.local()).build(0, cell, ids, 0);
    }
    advance(progress, range.size());
  });

  // Where each tree goes: its non-root nodes after the top cells', its
  // leaves and references after the previous trees'.
  std::vector<std::uint64_t> node_base(top_cells + 1), leaf_base(top_cells + 1), ref_base(top_cells + 1);
  node_base[0] = top_cells, leaf_base[0] = 0, ref_base[0] = 0;
  for (std::uint64_t c = 0; c < top_cells; ++c) {
    const bool top_leaf = trees[c].top_leaf;
    node_base[c + 1] = node_base[c] + (top_leaf ? 0 : trees[c].nodes.size() - 1);
    leaf_base[c + 1] = leaf_base[c] + (top_leaf ? 1 : trees[c].leaf_sizes.size());
    ref_base[c + 1] = ref_base[c] + (top_leaf ? top_offsets[c + 1] - top_offsets[c] : trees[c].refs.size());
    for (int k = 0; k < kMaxGrid2Levels; ++k) {
      m_info.refined += trees[c].refined[k];
      // A refined cell's node and its entry in m_leaf_of_node are its level's.
      m_info.level[k].bytes += trees[c].refined[k] * (sizeof(Node) + sizeof(std::uint32_t));
    }
  }
  const std::uint64_t nodes = node_base[top_cells], leaves = leaf_base[top_cells], refs = ref_base[top_cells];
  const std::uint64_t bytes = nodes * (sizeof(Node) + sizeof(std::uint32_t)) + (leaves + 1) * sizeof(std::uint32_t) +
                              refs * sizeof(TriangleId);
  if (nodes >= std::numeric_limits<std::uint32_t>::max() || refs >= std::numeric_limits<std::uint32_t>::max() ||
      bytes > options.max_bytes)
    throw InputError("grid2: " + std::to_string(leaves) + " leaves holding " + std::to_string(refs) +
                     " triangle references need " + byte_size(bytes) + ", over --grid-max-bytes (" +
                     byte_size(options.max_bytes) + ") or 2^32 - 1 cells or references");
  m_nodes.resize(nodes);
  m_offsets.resize(leaves + 1);
  m_leaf_of_node.resize(nodes);
  m_refs.resize(refs);
  m_leaf_level.resize(leaves);
  kappa::parallel_for(std::uint64_t(0), top_cells, [&](std::uint64_t c) {
    const LocalTree& tree = trees[c];
    if (tree.top_leaf) {
      const std::uint64_t first = top_offsets[c], n = top_offsets[c + 1] - first;
      m_nodes[c].index = std::uint32_t(leaf_base[c]);
      m_nodes[c].kind = n == 0 ? NestedGrid::empty : NestedGrid::list;
      m_offsets[leaf_base[c]] = std::uint32_t(ref_base[c]);
      m_leaf_level[leaf_base[c]] = 0;
      std::copy_n(top_lists.begin() + std::ptrdiff_t(first), n, m_refs.begin() + std::ptrdiff_t(ref_base[c]));
      return;
    }
    const auto global = [&](Node n) {
      n.index = std::uint32_t(n.kind == NestedGrid::refined ? node_base[c] + n.index - 1 : leaf_base[c] + n.index);
      return n;
    };
    m_nodes[c] = global(tree.nodes[0]);
    for (std::size_t j = 1; j < tree.nodes.size(); ++j) m_nodes[node_base[c] + j - 1] = global(tree.nodes[j]);
    std::uint64_t offset = ref_base[c];
    for (std::size_t j = 0; j < tree.leaf_sizes.size(); ++j) {
      m_offsets[leaf_base[c] + j] = std::uint32_t(offset);
      m_leaf_level[leaf_base[c] + j] = tree.leaf_levels[j];
      offset += tree.leaf_sizes[j];
    }
    std::copy(tree.refs.begin(), tree.refs.end(), m_refs.begin() + std::ptrdiff_t(ref_base[c]));
  });
  m_offsets[leaves] = std::uint32_t(refs);
  // The walk's form of the leaves: a list's bounds in its node, its leaf
  // number beside it (grid2.h, Node).
  kappa::parallel_for(tbb::blocked_range<std::uint64_t>(0, nodes), [&](const auto& range) {
    for (std::uint64_t i = range.begin(); i != range.end(); ++i) {
      Node& node = m_nodes[i];
      if (node.kind == NestedGrid::refined) {
        m_leaf_of_node[i] = NestedGrid::kNoLeaf;
        continue;
      }
      const std::uint32_t leaf = node.index;
      m_leaf_of_node[i] = leaf;
      const std::uint32_t begin = m_offsets[leaf], size = m_offsets[leaf + 1] - begin;
      node.index = begin;
      node.n[0] = std::uint8_t(std::min(size, NestedGrid::kLongList));
      node.n[1] = node.n[2] = 0;
    }
  });
  std::vector<TriangleId>().swap(top_lists);
  std::vector<LocalTree>().swap(trees);

  m_info.leaves = leaves;
  m_info.theta_tot = refs;
  m_info.bytes = bytes;
  for (int k = 0; k < kMaxGrid2Levels; ++k) m_info.level[k].level = k;
  for (std::uint64_t i = 0; i < leaves; ++i) {
    const std::uint32_t n = m_offsets[i + 1] - m_offsets[i];
    Grid2Level& level = m_info.level[m_leaf_level[i]];
    ++level.N_c;
    level.theta_tot += n;
    level.bytes += sizeof(Node) + 2 * sizeof(std::uint32_t) + n * sizeof(TriangleId);
    m_info.max_occupancy = std::max(m_info.max_occupancy, n);
    m_info.empty_leaves += n == 0;
    m_info.levels = std::max(m_info.levels, int(m_leaf_level[i]) + 1);
  }
  // The offsets' end goes with the top level: the levels' bytes add up to the whole.
  m_info.level[0].bytes += sizeof(std::uint32_t);
  m_info.build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace kappa
