// grid2's walk, templated on what it records (the protocol of recorder.h) as
// the uniform grid's is (grid_traverse.h): a 3D-DDA over the top grid that,
// in each refined cell, runs a DDA over that cell's sub-grid from where the
// ray entered it, and so on down the levels. Empty top cells cost one step.
#pragma once

#include <cfloat>
#include <cmath>
#include <limits>
#include <type_traits>

#include "grid2.h"
#include "grid_traverse.h"  // detail::Mailbox
#include "recorder.h"
#include "triangle4.h"

namespace kappa {

namespace detail {

/// One ray's walk through grid2: what every level's DDA shares.
template <GridWalk Mode, class Recorder, HitFilter Filter>
struct Grid2Walk {
  static constexpr bool AnyHit = Mode == GridWalk::any;
  static constexpr bool Closest = Mode == GridWalk::closest;
  /// Without a recorder nothing reads the counts, and the walk keeps none.
  static constexpr bool Records = !std::is_same_v<Recorder, NoRecorder>;

  Grid2Walk(const Ray& r, Hit& b, Recorder& rec, const Filter& f, const Triangle* tris, const std::uint32_t* offs,
            const std::uint32_t* leaves, const TriangleId* ids)
      : ray(r), prepared(r), best(b), recorder(rec), filter(f), triangles(tris), offsets(offs), leaf_of_node(leaves),
        refs(ids), o(r.o), d(r.d) {}

  const Ray& ray;
  const PreparedRay prepared;
  Hit& best;
  Recorder& recorder;
  const Filter& filter;
  const Triangle* triangles;
  const std::uint32_t* offsets;
  const std::uint32_t* leaf_of_node;
  const TriangleId* refs;
  Vec3d o, d;
  double inv_d[3] = {0, 0, 0};
  double margin_t = 0, t_end = 0;
  bool occluded = false;  ///< an any-hit walk found a hit
  Mailbox mailbox;
  /// Nothing at all without a recorder. Kept unused, the counts cost the
  /// bunny's stats-off frames 5 % once they grew from 128 to 136 bytes
  /// (descents): measured, not explained.
  struct NoCounts {};
  [[no_unique_address]] std::conditional_t<Records, WalkCounts, NoCounts> counts;

  /// Enters the leaf of node `index` (`node`) at `Level` and tests its
  /// triangles; true when an any-hit walk is done.
  template <int Level, class BoxFn>
  [[gnu::always_inline]] bool visit_leaf(const NestedGrid::Node& node, std::int64_t index, BoxFn&& box) {
    constexpr int level = Level;
    if constexpr (Records) {
      ++counts.cells;
      ++counts.level_cells[level];
      recorder.cell(leaf_of_node[index], level, box);
    }
    if (node.kind == NestedGrid::empty) return false;
    const std::uint32_t begin = node.index, size = node.n[0];
    const std::uint32_t end = size != NestedGrid::kLongList ? begin + size : offsets[leaf_of_node[index] + 1];
    if constexpr (Records)
      return test_one_at_a_time<Level>(begin, end);
    else
      return test_four_at_a_time(begin, end);
  }

  /// A leaf's list as a recorder sees it: each test counted and recorded as
  /// it is made; true when an any-hit walk is done.
  template <int Level>
  [[gnu::always_inline]] bool test_one_at_a_time(std::uint32_t begin, std::uint32_t end) {
    constexpr int level = Level;
    ++counts.occupied;
    counts.refs += end - begin;
    counts.level_refs[level] += end - begin;
    for (std::uint32_t k = begin; k < end; ++k) {
      const TriangleId id = refs[k];
      if (mailbox.seen(id)) {
        ++counts.skips;
        continue;
      }
      recorder.test();
      ++counts.tests;
      ++counts.level_tests[level];
      if constexpr (AnyHit) {
        if (test_any(prepared, triangles[id], id, ray.tmin, ray.tmax, filter)) {
          recorder.hit();
          occluded = true;
          best.triangle = id;  // the occluder (occluder_of)
          return true;
        }
      } else {
        const TriangleId before = best.triangle;
        const float before_t = best.t;
        test_closest(prepared, triangles[id], id, ray.tmin, best, filter);
        if (best.triangle != before || best.t != before_t) recorder.hit();
      }
    }
    return false;
  }

  /// A leaf's triangles not yet tested, four at a time (triangle4.h), when
  /// nothing is recorded (a recorder counts each test as the scalar loop
  /// makes it); true when an any-hit walk is done. The same verdicts, t and
  /// barycentrics as the scalar loop, in the same order.
  bool test_four_at_a_time(std::uint32_t begin, std::uint32_t end) {
    const Triangle* batch[4];
    TriangleId ids[4];
    int n = 0;
    for (std::uint32_t k = begin; k < end; ++k) {
      const TriangleId id = refs[k];
      if (mailbox.seen(id)) continue;
      batch[n] = &triangles[id];
      ids[n++] = id;
      if (n == 4) {
        if (test_batch(batch, ids, 4)) return true;
        n = 0;
      }
    }
    if (n == 1) return test_one(*batch[0], ids[0]);
    return n > 1 && test_batch(batch, ids, n);
  }

  [[gnu::always_inline]] bool test_one(const Triangle& triangle, TriangleId id) {
    if constexpr (AnyHit) {
      occluded = test_any(prepared, triangle, id, ray.tmin, ray.tmax, filter);
      if (occluded) best.triangle = id;  // the occluder (occluder_of)
      return occluded;
    } else {
      test_closest(prepared, triangle, id, ray.tmin, best, filter);
      return false;
    }
  }

  bool test_batch(const Triangle* const batch[4], const TriangleId ids[4], int n) {
    Lanes4 lanes;
    intersect4(prepared, batch, n, ray.tmin, lanes);
    // Lanes in list order, each against the limit the scalar loop would
    // have had after the lanes before it (test_closest's).
    for (int bits = lanes.valid | lanes.exact; bits != 0; bits &= bits - 1) {
      const int i = __builtin_ctz(unsigned(bits));
      if (lanes.exact >> i & 1) {
        if (test_one(*batch[i], ids[i])) return true;
        continue;
      }
      // The filter sees the lane's hit where the scalar test would have
      // shown it (test_any's and test_closest's order).
      if constexpr (AnyHit) {
        if (accept4(lanes, i, ray.tmin, ray.tmax) &&
            filter_accepts(filter, Hit{ids[i], lanes.t[i], lanes.b[0][i], lanes.b[1][i], lanes.b[2][i]})) {
          best.triangle = ids[i];  // the occluder (occluder_of)
          return occluded = true;
        }
      } else {
        if (accept4(lanes, i, ray.tmin, closest_limit(best)) && closer_than(lanes.t[i], ids[i], best)) {
          const Hit candidate{ids[i], lanes.t[i], lanes.b[0][i], lanes.b[1][i], lanes.b[2][i]};
          if (filter_accepts(filter, candidate)) best = candidate;
        }
      }
    }
    return false;
  }
};

/// What a sub-grid's walk ends with: go on along the parent, or stop the
/// whole walk (a hit settled, or the ray ended).
enum class SubWalk { go_on, stop };

}  // namespace detail

template <GridWalk Mode, class Recorder, int Level, class Walk>
bool NestedGrid::walk_sub_grid(const Node& node, const double lo[3], const double size[3], const double inv_size[3],
                               double t_enter, Walk& w, Recorder& recorder) const {
  static_assert(Level >= 1 && Level < kMaxGrid2Levels);
  // Returns true to stop the whole walk. The sub-grid's DDA starts at the
  // point where the ray entered the parent cell (clamped into it: that point
  // lies on its boundary, or before the box by the start margin).
  if constexpr (Walk::Records) ++w.counts.descents;
  const int n[3] = {node.n[0], node.n[1], node.n[2]};
  int s[3], step[3], last[3];
  double next[3], delta[3], l[3], inv_l[3];
  std::int64_t stride[3] = {1, n[0], std::int64_t(n[0]) * n[1]};
  std::int64_t child = node.index;
  for (int a = 0; a < 3; ++a) {
    l[a] = sub_cell_size(size[a], n[a]);
    inv_l[a] = inv_size[a] * n[a];  // 1 / l to rounding: only picks the entry cell, which is clamped
    const double p = w.o[a] + w.d[a] * t_enter;
    s[a] = int(std::clamp(std::floor((p - lo[a]) * inv_l[a]), 0.0, double(n[a] - 1)));
    child += s[a] * stride[a];
    if (w.d[a] > 0) {
      step[a] = 1;
      last[a] = n[a];
      next[a] = (lo[a] + (s[a] + 1) * l[a] - w.o[a]) * w.inv_d[a];
      delta[a] = l[a] * w.inv_d[a];
    } else if (w.d[a] < 0) {
      step[a] = -1;
      last[a] = -1;
      next[a] = (lo[a] + s[a] * l[a] - w.o[a]) * w.inv_d[a];
      delta[a] = -l[a] * w.inv_d[a];
      stride[a] = -stride[a];
    } else {
      step[a] = 0;
      last[a] = -2;
      next[a] = std::numeric_limits<double>::infinity();
      delta[a] = 0;
    }
  }
  double t_cell = t_enter;
  while (true) {
    const Node& c = m_nodes[std::size_t(child)];
    if (c.kind != refined) {
      if (w.template visit_leaf<Level>(c, child, [&] {
            const Vec3d cell_lo{lo[0] + s[0] * l[0], lo[1] + s[1] * l[1], lo[2] + s[2] * l[2]};
            return CellBox{cell_lo, cell_lo + Vec3d{l[0], l[1], l[2]}};
          }))
        return true;
    } else if constexpr (Level + 1 < kMaxGrid2Levels) {  // the build refines no cell of the last level
      const double child_lo[3] = {lo[0] + s[0] * l[0], lo[1] + s[1] * l[1], lo[2] + s[2] * l[2]};
      if (walk_sub_grid<Mode, Recorder, Level + 1>(c, child_lo, l, inv_l, t_cell, w, recorder)) return true;
    }
    const double exit = std::min(next[0], std::min(next[1], next[2]));
    if constexpr (Walk::Closest) {
      if (w.best.valid() && double(w.best.t) + w.margin_t < exit) return true;
    }
    if (!(exit <= w.t_end)) return true;
    t_cell = exit;
    const int a = next[0] <= next[1] && next[0] <= next[2] ? 0 : (next[1] <= next[2] ? 1 : 2);
    s[a] += step[a];
    if (s[a] == last[a]) return false;
    child += stride[a];
    next[a] += delta[a];
  }
}

template <GridWalk Mode, class Recorder, HitFilter Filter>
bool NestedGrid::traverse(const Ray& ray, Hit& best, Recorder& recorder, const Filter& filter) const {
  constexpr bool Closest = Mode == GridWalk::closest;
  if (m_refs.empty() || !is_finite(ray.o) || !is_finite(ray.d) || ray.d == Vec3f{0, 0, 0}) return false;
  if (!(ray.tmin <= ray.tmax)) return false;
  const GridInfo& g = m_info.top;
  detail::Grid2Walk<Mode, Recorder, Filter> w(ray, best, recorder, filter, m_triangles.data(), m_offsets.data(),
                                              m_leaf_of_node.data(), m_refs.data());
  const Vec3d& o = w.o;
  const Vec3d& d = w.d;

  // Clip [tmin, tmax] to the box, as the uniform grid does (grid_traverse.h).
  double t0 = double(ray.tmin), t1 = double(ray.tmax);
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (o[a] < g.lo[a] || o[a] > g.hi[a]) return false;
    } else {
      w.inv_d[a] = 1.0 / d[a];
      double tn = (g.lo[a] - o[a]) * w.inv_d[a], tf = (g.hi[a] - o[a]) * w.inv_d[a];
      if (tn > tf) std::swap(tn, tf);
      t0 = std::max(t0, tn);
      t1 = std::min(t1, tf);
    }
  }
  const double margin = std::max(g.margin, kMarginUlps * double(FLT_EPSILON) * double(max_component(abs(ray.o))));
  w.margin_t = margin / length(d);
  const double t_in = t0, t_out = t1;
  t0 = std::max(double(ray.tmin), t0 - w.margin_t);
  if (t0 > t1 + w.margin_t) return false;
  w.t_end = t1 + w.margin_t;
  const auto done = [&](bool result) __attribute__((always_inline)) {
    if constexpr (!std::is_same_v<Recorder, NoRecorder>) {
      const double ray_end = Closest ? double(best.t) : double(ray.tmax);
      recorder.finish(w.counts, WalkSegment{o, d, double(ray.tmin), t_in, t_out, ray_end});
    }
    return result;
  };

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
      t_next[a] = (g.lo[a] + (cell[a] + 1) * g.cell_size[a] - o[a]) * w.inv_d[a];
      t_delta[a] = g.cell_size[a] * w.inv_d[a];
    } else if (d[a] < 0) {
      step[a] = -1;
      last[a] = -1;
      t_next[a] = (g.lo[a] + cell[a] * g.cell_size[a] - o[a]) * w.inv_d[a];
      t_delta[a] = -g.cell_size[a] * w.inv_d[a];
      stride[a] = -stride[a];
    } else {
      step[a] = 0;
      last[a] = -2;
      t_next[a] = std::numeric_limits<double>::infinity();
      t_delta[a] = 0;
    }
  }
  const double size[3] = {g.cell_size.x, g.cell_size.y, g.cell_size.z};
  const double inv_size[3] = {m_inv_top.x, m_inv_top.y, m_inv_top.z};
  double tx = t_next[0], ty = t_next[1], tz = t_next[2];
  int ix = cell[0], iy = cell[1], iz = cell[2];
  double t_cell = t0;  // where the walk entered the current top cell
  while (true) {
    const Node& top = m_nodes[std::size_t(c)];
    if (top.kind != refined) {
      if (w.template visit_leaf<0>(top, c, [&] {
            const Vec3d lo = g.lo + Vec3d{double(ix), double(iy), double(iz)} * g.cell_size;
            return CellBox{lo, lo + g.cell_size};
          }))
        return done(true);
    } else {
      const double lo[3] = {g.lo.x + ix * size[0], g.lo.y + iy * size[1], g.lo.z + iz * size[2]};
      if (walk_sub_grid<Mode, Recorder, 1>(top, lo, size, inv_size, t_cell, w, recorder))
        return done(Mode == GridWalk::any ? w.occluded : best.valid());
    }
    // Leave the top cell through its nearest plane (ties: x, then y, then z).
    const double t_exit = std::min(tx, std::min(ty, tz));
    if constexpr (Closest) {
      if (best.valid() && double(best.t) + w.margin_t < t_exit) return done(true);
    }
    if (!(t_exit <= w.t_end)) break;
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

template <class Recorder, HitFilter Filter>
std::optional<Hit> NestedGrid::closest_hit(const Ray& ray, Recorder& recorder, const Filter& filter) const {
  Hit best;
  best.t = ray.tmax;
  if (!traverse<GridWalk::closest, Recorder, Filter>(ray, best, recorder, filter)) return std::nullopt;
  return best;
}

template <class Recorder, HitFilter Filter>
bool NestedGrid::any_hit(const Ray& ray, Recorder& recorder, const Filter& filter) const {
  Hit unused;
  return traverse<GridWalk::any, Recorder, Filter>(ray, unused, recorder, filter);
}

template <class Recorder, HitFilter Filter>
TriangleId NestedGrid::occluder_of(const Ray& ray, Recorder& recorder, const Filter& filter) const {
  Hit occluder;
  return traverse<GridWalk::any, Recorder, Filter>(ray, occluder, recorder, filter) ? occluder.triangle : kNoTriangle;
}

template <class Recorder>
std::optional<Hit> NestedGrid::walk_whole(const Ray& ray, Recorder& recorder) const {
  Hit best;
  best.t = ray.tmax;
  if (!traverse<GridWalk::whole>(ray, best, recorder)) return std::nullopt;
  return best;
}

}  // namespace kappa
