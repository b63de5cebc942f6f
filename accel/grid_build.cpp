// Building the uniform grid: bounds, resolution, then two parallel passes
// over the triangles (count per cell, then fill) into compressed rows.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/byte_size.h"
#include "core/check.h"
#include "core/input_error.h"
#include "core/parallel.h"
#include "core/physical_memory.h"
#include "grid.h"
#include "grid_insert.h"

namespace kappa {
namespace {

/// f(k) for k in [0, n) in parallel, counting each chunk done.
template <typename F>
void for_each_chunk(std::size_t n, TaskProgress* progress, F&& f) {
  kappa::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t k = range.begin(); k != range.end(); ++k) f(k);
    advance(progress, range.size());
  });
}

}  // namespace

std::uint64_t default_grid_max_bytes() { return physical_memory_bytes() / 4; }

GridBox grid_box(std::span<const Triangle> triangles) {
  // Bounds of the usable triangles, in double.
  Vec3d lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  bool any = false;
  for (const Triangle& t : triangles) {
    if (!usable_triangle(t)) continue;
    any = true;
    for (const Vec3f& v : {t.v0, t.v1, t.v2}) {
      lo = min(lo, Vec3d(v));
      hi = max(hi, Vec3d(v));
    }
  }
  if (!any) lo = hi = Vec3d{0, 0, 0};
  GridBox box;
  const double magnitude = std::max(max_component(abs(lo)), max_component(abs(hi))) + length(hi - lo);
  box.margin = kMarginUlps * double(FLT_EPSILON) * std::max(magnitude, double(FLT_MIN));
  box.lo = lo - Vec3d{box.margin, box.margin, box.margin};
  box.hi = hi + Vec3d{box.margin, box.margin, box.margin};
  return box;
}

OccupancyModel::OccupancyModel(std::span<const Triangle> triangles) {
  for (const Triangle& t : triangles) {
    if (!usable_triangle(t)) continue;
    const Vec3d a(t.v0), b(t.v1), c(t.v2);
    N += 1;
    extent_sum = extent_sum + (max(a, max(b, c)) - min(a, min(b, c)));
    // |n_a| * area is the area of the projection onto the plane normal to a.
    projected_sum = projected_sum + abs(cross(b - a, c - a)) * 0.5;
  }
}

double OccupancyModel::theta_tot(const Vec3d& l) const {
  return N + extent_sum.x / l.x + extent_sum.y / l.y + extent_sum.z / l.z + projected_sum.x / (l.y * l.z) +
         projected_sum.y / (l.x * l.z) + projected_sum.z / (l.x * l.y);
}

GridResolution bounded_resolution(const OccupancyModel& occupancy, const Vec3d& extent, GridResolution resolution) {
  const auto within = [&](const GridResolution& r) {
    const Vec3d cell{extent.x / r.nx, extent.y / r.ny, extent.z / r.nz};
    const double predicted = occupancy.theta_tot(cell);
    // Not finite: a zero-extent axis with one cell (a flat scene) is fine,
    // l there is 0 only when every triangle is flat along it too.
    return !(predicted > kThetaBoundPerTriangle * occupancy.N + double(r.cells()));
  };
  // Lower N_c by steps of 2^(1/4) until the prediction is within the bound.
  double target = double(resolution.cells());
  while (!within(resolution) && resolution.cells() > 1) {
    target /= 1.189207115002721;  // 2^(1/4)
    const GridResolution lower = choose_resolution(extent, std::max(1.0, target));
    if (lower.cells() < resolution.cells()) resolution = lower;
  }
  return resolution;
}

std::vector<TriangleId> usable_triangle_ids(std::span<const Triangle> triangles) {
  std::vector<TriangleId> ids;
  ids.reserve(triangles.size());
  for (TriangleId i = 0; i < TriangleId(triangles.size()); ++i)
    if (usable_triangle(triangles[i])) ids.push_back(i);
  return ids;
}

GridResolution density_resolution(const OccupancyModel& occupancy, const Vec3d& extent, double density, double N,
                                  std::uint64_t max_bytes) {
  const double cap = std::min(double(std::numeric_limits<std::uint32_t>::max() - 2), double(max_bytes) / 16.0);
  const GridResolution r = choose_resolution(extent, std::clamp(density * N, 1.0, std::max(1.0, cap)));
  return bounded_resolution(occupancy, extent, r);
}

UniformGrid::UniformGrid(std::span<const Triangle> triangles, const GridOptions& options, TaskProgress* progress)
    : m_triangles(triangles) {
  const auto start = std::chrono::steady_clock::now();
  if (triangles.size() >= std::size_t(kNoTriangle)) throw InputError("grid: more than 2^32 - 1 triangles");

  const std::vector<TriangleId> usable_ids = usable_triangle_ids(triangles);
  m_info.N = usable_ids.size();
  m_info.degenerate = triangles.size() - usable_ids.size();
  const GridBox box = grid_box(triangles);
  m_info.margin = box.margin;
  m_info.lo = box.lo;
  m_info.hi = box.hi;
  if (options.box) {
    m_info.lo = options.box->first;
    m_info.hi = options.box->second;
  }
  const Vec3d extent = m_info.hi - m_info.lo;

  if (options.resolution) {
    m_info.resolution = *options.resolution;
  } else {
    const OccupancyModel occupancy = options.occupancy ? *options.occupancy : OccupancyModel(triangles);
    m_info.resolution = density_resolution(occupancy, extent, options.density, double(m_info.N), options.max_bytes);
  }
  const std::uint64_t cells = m_info.resolution.cells();
  // Offsets, with the occupancy bits.
  const std::uint64_t offset_bytes = (cells + 1) * sizeof(std::uint32_t) + (cells + 63) / 64 * sizeof(std::uint64_t);
  if (cells >= std::numeric_limits<std::uint32_t>::max())
    throw InputError("grid: " + m_info.resolution.to_string() + " = " + std::to_string(cells) +
                                " cells, over the 2^32 - 1 a grid can index");
  if (offset_bytes > options.max_bytes)
    throw InputError("grid: " + m_info.resolution.to_string() + " = " + std::to_string(cells) +
                                " cells need " + byte_size(offset_bytes) +
                                " for cell offsets alone, over --grid-max-bytes (" +
                                byte_size(options.max_bytes) + ")");
  for (int a = 0; a < 3; ++a) {
    const double l = extent[a] / m_info.resolution[a];
    (a == 0 ? m_info.cell_size.x : a == 1 ? m_info.cell_size.y : m_info.cell_size.z) = l;
    (a == 0 ? m_inv_cell.x : a == 1 ? m_inv_cell.y : m_inv_cell.z) = 1.0 / l;
  }

  // The cells to fill, asked of the grid while it is empty (a walk of it
  // visits what the filled grid's walk visits: the cells follow the box, not
  // the lists). A partial grid keeps offsets for those cells alone, each at
  // its slot().
  std::uint64_t slots = cells;
  if (options.cells_to_fill) {
    m_occupied.assign((cells + 63) / 64, 0);  // the empty grid's walk reads these, never an offset
    m_filled = options.cells_to_fill(*this);
    KAPPA_CHECK_EQ(m_filled.size(), (cells + 63) / 64);
    m_filled_rank.resize(m_filled.size());
    std::uint64_t rank = 0;
    for (std::size_t w = 0; w < m_filled.size(); ++w) {
      m_filled_rank[w] = std::uint32_t(rank);
      rank += std::uint64_t(std::popcount(m_filled[w]));
    }
    slots = rank;
    m_info.partial = true;
  }
  const auto filled = [this](std::uint64_t c) { return this->filled(c); };

  // Pass 1: count the triangles of each cell. A partial grid also keeps what
  // it found, block by block (a block's pairs in ascending id), and is filled
  // from those pairs below: its second clipping of every triangle cost the
  // dragon's counting grid 0.065 s of the 0.22 s auto's choice adds to
  // grid2's build, for the few references the filled cells hold.
  m_offsets.assign(slots + 1, 0);
  begin_phase(progress, "grid " + m_info.resolution.to_string() + ": counting cells", usable_ids.size());
  std::atomic<std::uint64_t> max_multiplicity{0};
  const auto keep_largest_multiplicity = [&](std::uint64_t cells_of_triangle) {
    // The paper's multiplicity M_j of this triangle; the largest is kept.
    std::uint64_t seen = max_multiplicity.load(std::memory_order_relaxed);
    while (cells_of_triangle > seen && !max_multiplicity.compare_exchange_weak(seen, cells_of_triangle)) {
    }
  };
  using SlotRef = std::pair<std::uint32_t, TriangleId>;  // (slot, triangle)
  constexpr std::size_t kBlock = 4096;
  // Held before the budget is checked, 8 bytes a reference: bounded_resolution
  // keeps a grid's predicted Theta_tot within 16 N + N_c.
  std::vector<std::vector<SlotRef>> found;
  if (m_info.partial) {
    found.resize((usable_ids.size() + kBlock - 1) / kBlock);
    kappa::parallel_for(std::size_t(0), found.size(), [&](std::size_t b) {
      const std::size_t end = std::min(usable_ids.size(), (b + 1) * kBlock);
      for (std::size_t k = b * kBlock; k < end; ++k) {
        const TriangleId id = usable_ids[k];
        std::uint64_t cells_of_triangle = 0;
        for_each_overlapped_cell(m_info, m_inv_cell, triangles[id], [&](std::uint64_t c) {
          found[b].emplace_back(std::uint32_t(slot(c)), id);
          ++cells_of_triangle;
        }, filled);
        keep_largest_multiplicity(cells_of_triangle);
      }
      advance(progress, end - b * kBlock);
    });
    for (const std::vector<SlotRef>& block : found)
      for (const SlotRef& ref : block) ++m_offsets[ref.first];
  } else {
    for_each_chunk(usable_ids.size(), progress, [&](std::size_t k) {
      std::uint64_t cells_of_triangle = 0;
      for_each_overlapped_cell(m_info, m_inv_cell, triangles[usable_ids[k]], [&](std::uint64_t c) {
        std::atomic_ref<std::uint32_t>(m_offsets[c]).fetch_add(1, std::memory_order_relaxed);
        ++cells_of_triangle;
      });
      keep_largest_multiplicity(cells_of_triangle);
    });
  }
  m_info.max_multiplicity = max_multiplicity.load();
  // Inclusive prefix sum into offsets (each cell's end; pass 2 counts them
  // down to each cell's start), the occupancy bits from the counts; 64-bit
  // total to detect overflow.
  // A partial grid's bits are still the zeros its empty walk read.
  if (!m_info.partial) m_occupied.assign((cells + 63) / 64, 0);
  std::uint64_t total = 0;
  const auto add_cell = [&](std::uint64_t c, std::size_t s) {
    const std::uint32_t n = m_offsets[s];
    m_info.max_occupancy = std::max(m_info.max_occupancy, n);
    if (n != 0) m_occupied[c >> 6] |= std::uint64_t(1) << (c & 63);
    total += n;
    m_offsets[s] = std::uint32_t(std::min<std::uint64_t>(total, std::numeric_limits<std::uint32_t>::max()));
    return n == 0;
  };
  if (m_info.partial) {
    std::size_t s = 0;
    for (std::size_t w = 0; w < m_filled.size(); ++w)
      for (std::uint64_t bits = m_filled[w]; bits != 0; bits &= bits - 1)
        m_info.empty_cells += add_cell(std::uint64_t(w) * 64 + std::uint64_t(std::countr_zero(bits)), s++);
    m_info.empty_cells += cells - slots;  // the cells left unfilled hold nothing
  } else {
    for (std::uint64_t c = 0; c < cells; ++c) m_info.empty_cells += add_cell(c, std::size_t(c));
  }
  const std::uint64_t held_offset_bytes =
      m_info.partial ? (slots + 1) * sizeof(std::uint32_t) + (cells + 63) / 64 * (2 * sizeof(std::uint64_t) + sizeof(std::uint32_t))
                     : offset_bytes;
  const std::uint64_t bytes = held_offset_bytes + total * sizeof(TriangleId);
  if (total >= std::numeric_limits<std::uint32_t>::max() || bytes > options.max_bytes)
    throw InputError("grid: " + m_info.resolution.to_string() + " holds " + std::to_string(total) +
                                " triangle references (" + byte_size(bytes) + "), over --grid-max-bytes (" +
                                byte_size(options.max_bytes) + ") or 2^32 - 1 references");
  m_offsets[slots] = std::uint32_t(total);
  m_info.theta_tot = total;
  m_info.bytes = bytes;  // offset_bytes already counts the occupancy bits

  m_refs.resize(total);
  if (m_info.partial) {
    // Taken last to first and counted down: each cell's ids come out
    // ascending, as the whole grid's sort leaves them.
    for (auto block = found.rbegin(); block != found.rend(); ++block)
      for (auto ref = block->rbegin(); ref != block->rend(); ++ref) m_refs[--m_offsets[ref->first]] = ref->second;
    KAPPA_CHECK_EQ(m_offsets[0], 0u);
    m_info.build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return;
  }

  // Pass 2: fill, each cell from its end down, so that its offset ends at its
  // start without a second array of cursors (which cost a copy of the
  // offsets, and on these VMs as much again in page faults). Threads race
  // for slots within a cell, so each cell is sorted afterwards: the layout
  // (and anything counted over it) does not depend on scheduling.
  begin_phase(progress, "grid " + m_info.resolution.to_string() + ": filling cells", usable_ids.size());
  for_each_chunk(usable_ids.size(), progress, [&](std::size_t k) {
    const TriangleId id = usable_ids[k];
    const auto place = [&](std::uint64_t c) {
      const std::uint32_t end = std::atomic_ref<std::uint32_t>(m_offsets[c]).fetch_sub(1, std::memory_order_relaxed);
      // Pass 1 counted exactly the cells pass 2 visits: a cell counted down
      // past its start would write into the previous cell's references, and
      // past 0 before the array.
      KAPPA_CHECK_GT(end, 0u);
      m_refs[end - 1] = id;
    };
    for_each_overlapped_cell(m_info, m_inv_cell, triangles[id], place);
  });
  KAPPA_CHECK_EQ(m_offsets[0], 0u);
  kappa::parallel_for(std::uint64_t(0), slots, [&](std::uint64_t s) {
    std::sort(m_refs.begin() + m_offsets[s], m_refs.begin() + m_offsets[s + 1]);
  });
  m_info.build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace kappa
