// The grid walk, templated on what it records (the protocol of recorder.h,
// which stats/counters.h implements): the
// renderer's hot path instantiates it with a recorder whose methods are empty,
// so statistics that are off cost nothing; `kappa cast` and stats-on renders
// instantiate it with per-cell counters. Included by grid.cpp and by code that
// walks the grid with a recorder.
#pragma once

#include <cfloat>
#include <cmath>
#include <limits>
#include <type_traits>

#include "core/check.h"
#include "grid.h"
#include "recorder.h"

namespace kappa {

namespace detail {

/// Tests each triangle at most once per ray although it may sit in many
/// cells: a small direct-mapped cache of recently tested ids on the stack (no
/// allocation, no per-thread state). A collision only costs a repeated test,
/// which gives the same answer.
class Mailbox {
 public:
  Mailbox() {
    for (TriangleId& id : m_ids) id = kNoTriangle;
  }
  /// True if `id` was already tested; otherwise records it.
  bool seen(TriangleId id) {
    TriangleId& slot = m_ids[id & (kSize - 1)];
    if (slot == id) return true;
    slot = id;
    return false;
  }

 private:
  static constexpr std::uint32_t kSize = 16;
  TriangleId m_ids[kSize];
};

}  // namespace detail

template <GridWalk Mode, class Recorder, bool TestTriangles, HitFilter Filter>
bool UniformGrid::traverse(const Ray& ray, Hit& best, Recorder& recorder, const Filter& filter) const {
  constexpr bool AnyHit = Mode == GridWalk::any;
  constexpr bool Whole = Mode == GridWalk::whole;
  if constexpr (TestTriangles) KAPPA_DCHECK(!m_info.partial);  // a partial grid counts; its hits would be wrong
  // Non-finite rays and d = 0 hit nothing (as in naive, whose test yields NaN).
  // A grid without references hits nothing; a counting walk still walks it
  // (a counting grid's cells are found by walking it empty).
  if ((TestTriangles && m_refs.empty()) || !is_finite(ray.o) || !is_finite(ray.d) || ray.d == Vec3f{0, 0, 0}) return false;
  if (!(ray.tmin <= ray.tmax)) return false;  // also NaN bounds: naive misses these too
  const Vec3d o(ray.o), d(ray.d);
  const GridInfo& g = m_info;

  // Clip [tmin, tmax] to the grid box. Float directions are normal numbers
  // in double (even float subnormals), so 1/d is finite for d != 0; d = +-0
  // is handled apart, without dividing.
  double t0 = double(ray.tmin), t1 = double(ray.tmax);
  Vec3d inv_d;
  for (int a = 0; a < 3; ++a) {
    double inv = 0;
    if (d[a] == 0.0) {
      if (o[a] < g.lo[a] || o[a] > g.hi[a]) return false;
    } else {
      inv = 1.0 / d[a];
      double tn = (g.lo[a] - o[a]) * inv, tf = (g.hi[a] - o[a]) * inv;
      if (tn > tf) std::swap(tn, tf);
      t0 = std::max(t0, tn);
      t1 = std::min(t1, tf);
    }
    (a == 0 ? inv_d.x : a == 1 ? inv_d.y : inv_d.z) = inv;
  }
  // A hit found within `margin_t` of a cell's exit may still be beaten by a
  // triangle of the next cell whose float test rounds the other way: walk
  // one more cell in that case.
  // The float test's rounding grows with |vertex - origin|: an origin far
  // outside the scene widens the margin (but not the cells' insertion margin,
  // which covers origins within a few scene diagonals; see grid.h).
  const double margin = std::max(g.margin, kMarginUlps * double(FLT_EPSILON) * double(max_component(abs(ray.o))));
  const double margin_t = margin / length(d);
  const double t_in = t0, t_out = t1;  // the ray's part inside the grid box
  t0 = std::max(double(ray.tmin), t0 - margin_t);
  if (t0 > t1 + margin_t) return false;

  // Entry cell and, per axis, the step, the t of the next cell plane and the
  // t between planes. Accumulating t_delta in double drifts by ~1e-13 of t
  // over thousands of steps, far inside the cells' insertion margin.
  int cell[3], step[3], last[3];
  double t_next[3], t_delta[3];
  std::int64_t stride[3] = {1, g.resolution.nx, std::int64_t(g.resolution.nx) * g.resolution.ny};
  const Vec3d entry = o + d * t0;
  std::int64_t c = 0;
  for (int a = 0; a < 3; ++a) {
    const int n = g.resolution[a];
    // Clamped in double before the conversion: the entry point may lie far
    // outside the grid (the start margin grows with |origin|), billions of
    // cells away, which no int holds.
    cell[a] = int(std::clamp(std::floor((entry[a] - g.lo[a]) * m_inv_cell[a]), 0.0, double(n - 1)));
    c += cell[a] * stride[a];
    if (d[a] > 0) {
      step[a] = 1;
      last[a] = n;
      t_next[a] = (g.lo[a] + (cell[a] + 1) * g.cell_size[a] - o[a]) * inv_d[a];
      t_delta[a] = g.cell_size[a] * inv_d[a];
    } else if (d[a] < 0) {
      step[a] = -1;
      last[a] = -1;
      t_next[a] = (g.lo[a] + cell[a] * g.cell_size[a] - o[a]) * inv_d[a];
      t_delta[a] = -g.cell_size[a] * inv_d[a];
      stride[a] = -stride[a];
    } else {
      step[a] = 0;
      last[a] = -2;  // never reached
      t_next[a] = std::numeric_limits<double>::infinity();
      t_delta[a] = 0;
    }
  }

  const PreparedRay prepared(ray);
  detail::Mailbox mailbox;
  WalkCounts counts;
  // The walk's state in scalars, so that it stays in registers.
  double tx = t_next[0], ty = t_next[1], tz = t_next[2];
  const double dx = t_delta[0], dy = t_delta[1], dz = t_delta[2];
  int ix = cell[0], iy = cell[1], iz = cell[2];
  const auto done = [&](bool result) __attribute__((always_inline)) {
    if constexpr (!std::is_same_v<Recorder, NoRecorder>) {
      // Cells visited, from where the walk started and stopped rather than a
      // counter in the loop (exact for this walk, which moves one index by
      // one at each step; a walk that skips or has levels counts per step):
      // a walk that left the grid has one index on its `last` value.
      const bool left = ix == last[0] || iy == last[1] || iz == last[2];
      counts.cells =
          std::uint64_t(1 + std::abs(ix - cell[0]) + std::abs(iy - cell[1]) + std::abs(iz - cell[2])) - left;
      const double ray_end = Mode == GridWalk::closest ? double(best.t) : double(ray.tmax);
      recorder.finish(counts, WalkSegment{o, d, double(ray.tmin), t_in, t_out, ray_end});
    }
    return result;
  };
  const double t_end = t1 + margin_t;
  while (true) {
    recorder.cell(std::uint64_t(c), 0, [&] {  // the cell's box, only if the recorder asks
      const Vec3d lo = g.lo + Vec3d{double(ix), double(iy), double(iz)} * g.cell_size;
      return CellBox{lo, lo + g.cell_size};
    });
    // Empty cells (most of them) do nothing more: no offsets, no counts.
    if ((m_occupied[std::size_t(c) >> 6] >> (std::size_t(c) & 63)) & 1) {
      // A partial grid (counting only) stores its filled cells' offsets alone.
      const std::size_t s = TestTriangles ? std::size_t(c) : slot(std::uint64_t(c));
      const std::uint32_t begin = m_offsets[s], end = m_offsets[s + 1];
      ++counts.occupied;
      counts.refs += end - begin;
      for (std::uint32_t k = begin; k < end; ++k) {
        const TriangleId id = m_refs[k];
        if (mailbox.seen(id)) {
          ++counts.skips;
          continue;
        }
        recorder.test();
        ++counts.tests;
        if constexpr (!TestTriangles) {
          continue;  // counting only: `best` already holds the hit the walk would find
        } else if constexpr (AnyHit) {
          if (test_any(prepared, m_triangles[id], id, ray.tmin, ray.tmax, filter)) {
            recorder.hit();
            best.triangle = id;  // the occluder (occluder_of): an any-hit walk keeps no t
            return done(true);
          }
        } else {
          const TriangleId before = best.triangle;
          const float before_t = best.t;
          test_closest(prepared, m_triangles[id], id, ray.tmin, best, filter);
          if (best.triangle != before || best.t != before_t) recorder.hit();
        }
      }
    }
    // Leave through the nearest cell plane; on exact ties x, then y, then z.
    // At least one axis moves (d != 0), so the nearest plane is finite while
    // t_end is, and an axis that does not move is never the nearest.
    const double t_exit = std::min(tx, std::min(ty, tz));
    if constexpr (!AnyHit && !Whole) {
      if (best.valid() && double(best.t) + margin_t < t_exit) return done(true);
    }
    if (!(t_exit <= t_end)) break;
    if (tx <= ty && tx <= tz) {
      ix += step[0];
      if (ix == last[0]) break;
      c += stride[0];
      tx += dx;
    } else if (ty <= tz) {
      iy += step[1];
      if (iy == last[1]) break;
      c += stride[1];
      ty += dy;
    } else {
      iz += step[2];
      if (iz == last[2]) break;
      c += stride[2];
      tz += dz;
    }
  }
  return done(best.valid());
}

template <class Recorder, HitFilter Filter>
std::optional<Hit> UniformGrid::closest_hit(const Ray& ray, Recorder& recorder, const Filter& filter) const {
  Hit best;
  best.t = ray.tmax;
  if (!traverse<GridWalk::closest, Recorder, true, Filter>(ray, best, recorder, filter)) return std::nullopt;
  return best;
}

template <class Recorder, HitFilter Filter>
bool UniformGrid::any_hit(const Ray& ray, Recorder& recorder, const Filter& filter) const {
  Hit unused;
  return traverse<GridWalk::any, Recorder, true, Filter>(ray, unused, recorder, filter);
}

template <class Recorder, HitFilter Filter>
TriangleId UniformGrid::occluder_of(const Ray& ray, Recorder& recorder, const Filter& filter) const {
  Hit occluder;
  return traverse<GridWalk::any, Recorder, true, Filter>(ray, occluder, recorder, filter) ? occluder.triangle
                                                                                          : kNoTriangle;
}

template <class Recorder>
void UniformGrid::count_closest_walk(const Ray& ray, std::optional<float> t_hit, Recorder& recorder) const {
  // With the final hit in `best` from the start, the walk stops at the cell
  // where the real one stops: the real walk's best only falls to this t, and
  // the triangle that gives it is tested no later than in the cell that
  // holds the hit point, whose exit is the first beyond it.
  Hit best;
  best.t = t_hit.value_or(ray.tmax);
  best.triangle = t_hit ? 0 : kNoTriangle;
  traverse<GridWalk::closest, Recorder, false>(ray, best, recorder);
}

template <class Recorder>
std::optional<Hit> UniformGrid::walk_whole(const Ray& ray, Recorder& recorder) const {
  Hit best;
  best.t = ray.tmax;
  if (!traverse<GridWalk::whole>(ray, best, recorder)) return std::nullopt;
  return best;
}

}  // namespace kappa
