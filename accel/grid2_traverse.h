// grid2's walk, templated on what it records (the protocol of recorder.h) as
// the uniform grid's is (grid_traverse.h): a 3D-DDA over the top grid that,
// in each top cell holding triangles, runs a second DDA over that cell's
// sub-grid from where the ray entered it. Empty top cells cost one step.
#pragma once

#include <cfloat>
#include <cmath>
#include <limits>
#include <type_traits>

#include "grid2.h"
#include "grid_traverse.h"  // detail::Mailbox
#include "recorder.h"

namespace kappa {

template <GridWalk Mode, class Recorder>
bool TwoLevelGrid::traverse(const Ray& ray, Hit& best, Recorder& recorder) const {
  constexpr bool AnyHit = Mode == GridWalk::any;
  constexpr bool Whole = Mode == GridWalk::whole;
  constexpr bool Closest = !AnyHit && !Whole;
  if (m_refs.empty() || !is_finite(ray.o) || !is_finite(ray.d) || ray.d == Vec3f{0, 0, 0}) return false;
  if (!(ray.tmin <= ray.tmax)) return false;
  const Vec3d o(ray.o), d(ray.d);
  const GridInfo& g = m_info.top;

  // Clip [tmin, tmax] to the box, as the uniform grid does (grid_traverse.h).
  double t0 = double(ray.tmin), t1 = double(ray.tmax);
  double inv_d[3];
  for (int a = 0; a < 3; ++a) {
    inv_d[a] = 0;
    if (d[a] == 0.0) {
      if (o[a] < g.lo[a] || o[a] > g.hi[a]) return false;
    } else {
      inv_d[a] = 1.0 / d[a];
      double tn = (g.lo[a] - o[a]) * inv_d[a], tf = (g.hi[a] - o[a]) * inv_d[a];
      if (tn > tf) std::swap(tn, tf);
      t0 = std::max(t0, tn);
      t1 = std::min(t1, tf);
    }
  }
  const double margin = std::max(g.margin, kMarginUlps * double(FLT_EPSILON) * double(max_component(abs(ray.o))));
  const double margin_t = margin / length(d);
  const double t_in = t0, t_out = t1;
  t0 = std::max(double(ray.tmin), t0 - margin_t);
  if (t0 > t1 + margin_t) return false;
  const double t_end = t1 + margin_t;

  // The top grid's DDA.
  int cell[3], step[3], last[3];
  double t_next[3], t_delta[3];
  std::int64_t stride[3] = {1, g.resolution.nx, std::int64_t(g.resolution.nx) * g.resolution.ny};
  const Vec3d entry = o + d * t0;
  std::int64_t c = 0;
  for (int a = 0; a < 3; ++a) {
    const int n = g.resolution[a];
    cell[a] = int(std::clamp(std::floor((entry[a] - g.lo[a]) * m_inv_top[a]), 0.0, double(n - 1)));
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
      last[a] = -2;
      t_next[a] = std::numeric_limits<double>::infinity();
      t_delta[a] = 0;
    }
  }

  const PreparedRay prepared(ray);
  detail::Mailbox mailbox;
  WalkCounts counts;
  const auto done = [&](bool result) __attribute__((always_inline)) {
    if constexpr (!std::is_same_v<Recorder, NoRecorder>) {
      const double ray_end = Closest ? double(best.t) : double(ray.tmax);
      recorder.finish(counts, WalkSegment{o, d, double(ray.tmin), t_in, t_out, ray_end});
    }
    return result;
  };
  // Tests leaf `leaf`'s triangles; true when an any-hit walk is done.
  const auto test_leaf = [&](std::uint64_t leaf) __attribute__((always_inline)) {
    const std::uint32_t begin = m_offsets[std::size_t(leaf)], end = m_offsets[std::size_t(leaf) + 1];
    if (begin == end) return false;
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
      if constexpr (AnyHit) {
        float t, b0, b1, b2;
        if (intersect_triangle(prepared, m_triangles[id], ray.tmin, ray.tmax, t, b0, b1, b2)) {
          recorder.hit();
          return true;
        }
      } else {
        const TriangleId before = best.triangle;
        const float before_t = best.t;
        test_closest(prepared, m_triangles[id], id, ray.tmin, best);
        if (best.triangle != before || best.t != before_t) recorder.hit();
      }
    }
    return false;
  };

  double tx = t_next[0], ty = t_next[1], tz = t_next[2];
  int ix = cell[0], iy = cell[1], iz = cell[2];
  double t_cell = t0;  // where the walk entered the current top cell
  while (true) {
    const TopCell top = m_top[std::size_t(c)];
    ++counts.cells;
    if (!top.occupied) {
      ++counts.top_cells;
      recorder.cell(top.first_leaf, 0, [&] { return top_box(ix, iy, iz); });
    } else {
      // The sub-grid's DDA, from the point where the ray entered this top
      // cell (clamped into it: that point lies on its boundary, or before
      // the box by the start margin). Leaves are numbered x fastest.
      const int sn[3] = {top.n[0], top.n[1], top.n[2]};
      const int ti[3] = {ix, iy, iz};
      int s[3], sstep[3], slast[3];
      double snext[3], sdelta[3];
      std::int64_t sstride[3] = {1, sn[0], std::int64_t(sn[0]) * sn[1]};
      double slo[3], sl[3];
      const Vec3d p = o + d * t_cell;
      std::int64_t leaf = top.first_leaf;
      for (int a = 0; a < 3; ++a) {
        sl[a] = g.cell_size[a] / sn[a];
        slo[a] = g.lo[a] + ti[a] * g.cell_size[a];
        s[a] = int(std::clamp(std::floor((p[a] - slo[a]) / sl[a]), 0.0, double(sn[a] - 1)));
        leaf += s[a] * sstride[a];
        if (d[a] > 0) {
          sstep[a] = 1;
          slast[a] = sn[a];
          snext[a] = (slo[a] + (s[a] + 1) * sl[a] - o[a]) * inv_d[a];
          sdelta[a] = sl[a] * inv_d[a];
        } else if (d[a] < 0) {
          sstep[a] = -1;
          slast[a] = -1;
          snext[a] = (slo[a] + s[a] * sl[a] - o[a]) * inv_d[a];
          sdelta[a] = -sl[a] * inv_d[a];
          sstride[a] = -sstride[a];
        } else {
          sstep[a] = 0;
          slast[a] = -2;
          snext[a] = std::numeric_limits<double>::infinity();
          sdelta[a] = 0;
        }
      }
      --counts.cells;  // the top cell itself is not a leaf: its sub-grid's cells are
      while (true) {
        ++counts.cells;
        recorder.cell(std::uint64_t(leaf), 1, [&] {
          const Vec3d lo{slo[0] + s[0] * sl[0], slo[1] + s[1] * sl[1], slo[2] + s[2] * sl[2]};
          return CellBox{lo, lo + Vec3d{sl[0], sl[1], sl[2]}};
        });
        if (test_leaf(std::uint64_t(leaf))) return done(true);
        const double s_exit = std::min(snext[0], std::min(snext[1], snext[2]));
        if constexpr (Closest) {
          if (best.valid() && double(best.t) + margin_t < s_exit) return done(true);
        }
        if (!(s_exit <= t_end)) return done(best.valid());
        const int a = snext[0] <= snext[1] && snext[0] <= snext[2] ? 0 : (snext[1] <= snext[2] ? 1 : 2);
        s[a] += sstep[a];
        if (s[a] == slast[a]) break;
        leaf += sstride[a];
        snext[a] += sdelta[a];
      }
    }
    // Leave the top cell through its nearest plane (ties: x, then y, then z).
    const double t_exit = std::min(tx, std::min(ty, tz));
    if constexpr (Closest) {
      if (best.valid() && double(best.t) + margin_t < t_exit) return done(true);
    }
    if (!(t_exit <= t_end)) break;
    t_cell = t_exit;
    if (tx <= ty && tx <= tz) {
      ix += step[0];
      if (ix == last[0]) break;
      c += stride[0];
      tx += t_delta[0];
    } else if (ty <= tz) {
      iy += step[1];
      if (iy == last[1]) break;
      c += stride[1];
      ty += t_delta[1];
    } else {
      iz += step[2];
      if (iz == last[2]) break;
      c += stride[2];
      tz += t_delta[2];
    }
  }
  return done(best.valid());
}

template <class Recorder>
std::optional<Hit> TwoLevelGrid::closest_hit(const Ray& ray, Recorder& recorder) const {
  Hit best;
  best.t = ray.tmax;
  if (!traverse<GridWalk::closest>(ray, best, recorder)) return std::nullopt;
  return best;
}

template <class Recorder>
bool TwoLevelGrid::any_hit(const Ray& ray, Recorder& recorder) const {
  Hit unused;
  return traverse<GridWalk::any>(ray, unused, recorder);
}

template <class Recorder>
std::optional<Hit> TwoLevelGrid::walk_whole(const Ray& ray, Recorder& recorder) const {
  Hit best;
  best.t = ray.tmax;
  if (!traverse<GridWalk::whole>(ray, best, recorder)) return std::nullopt;
  return best;
}

}  // namespace kappa
