// The any-hit filter seam (accel/hit_filter.h): naive, grid and grid2 asked
// with one filter return bitwise the same closest hit and occlusion, and that
// answer is naive's over the triangles the filter refuses taken out of the
// scene (made degenerate, so ids stay). Grid2's walk without a recorder tests
// four triangles at a time, with one the scalar loop: both are checked, and
// both ask the filter exactly what a scalar loop over the leaves the walk
// visits asks, in the same order.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "accel/grid.h"
#include "accel/grid2.h"
#include "accel/grid2_traverse.h"
#include "accel/grid_traverse.h"
#include "accel/naive.h"
#include "agreement.h"
#include "test_util.h"

namespace kappa::test {
namespace {

/// Refuses every triangle whose id is in `refused` (a cut-out's shape: some
/// triangles are holes).
struct RefuseIds {
  static constexpr bool active = true;
  const std::vector<bool>* refused;
  mutable std::uint64_t calls = 0;
  bool accepts(const Hit& h) const {
    ++calls;
    return !(*refused)[h.triangle];
  }
};
static_assert(HitFilter<RefuseIds>);
static_assert(HitFilter<NoHitFilter> && !NoHitFilter::active);

/// Refuses a hit by where it lies on its triangle (b1 > b2): half of each
/// triangle is a hole, so the same triangle counts for one ray and not for
/// another, as an alpha map's texels do.
struct RefuseHalf {
  static constexpr bool active = true;
  bool accepts(const Hit& h) const { return !(h.b1 > h.b2); }
};

/// A recorder that records nothing but is not NoRecorder: grid2's scalar loop.
struct AnyRecorder : NoRecorder {};

/// The leaves a walk visits, in order (a recorder: grid2's scalar loop).
struct LeafRecorder : NoRecorder {
  std::vector<std::uint64_t> leaves;
  template <class BoxFn>
  void cell(std::uint64_t leaf, int, BoxFn&&) {
    leaves.push_back(leaf);
  }
};

/// Every candidate the filter is asked about, in order (id and t's bits);
/// refuses the ids in `refused`.
struct CallLog {
  static constexpr bool active = true;
  const std::vector<bool>* refused;
  mutable std::vector<std::pair<TriangleId, std::uint32_t>> calls;
  bool accepts(const Hit& h) const {
    calls.emplace_back(h.triangle, std::bit_cast<std::uint32_t>(h.t));
    return !(*refused)[h.triangle];
  }
};

bool same(const std::optional<Hit>& a, const std::optional<Hit>& b) {
  if (a.has_value() != b.has_value()) return false;
  return !a || (a->triangle == b->triangle && std::bit_cast<std::uint32_t>(a->t) == std::bit_cast<std::uint32_t>(b->t) &&
                std::bit_cast<std::uint32_t>(a->b0) == std::bit_cast<std::uint32_t>(b->b0) &&
                std::bit_cast<std::uint32_t>(a->b1) == std::bit_cast<std::uint32_t>(b->b1) &&
                std::bit_cast<std::uint32_t>(a->b2) == std::bit_cast<std::uint32_t>(b->b2));
}

template <class Filter>
void expect_all_agree(const std::vector<Triangle>& tris, const Filter& filter, const std::vector<Triangle>* holes_removed,
                      std::size_t& filtered_hits) {
  const NaiveAccelerator naive(tris);
  const UniformGrid grid(tris, GridOptions{});
  const NestedGrid grid2(tris, Grid2Options{});
  std::optional<NaiveAccelerator> reference;
  if (holes_removed) reference.emplace(*holes_removed);
  NoRecorder none;
  AnyRecorder counting;
  std::size_t mismatches = 0;
  for (const Ray& r : ray_families(tris, grid, 300, 7)) {
    const auto n = naive.closest_hit(r, filter);
    const bool n_any = naive.any_hit(r, filter);
    filtered_hits += !same(n, naive.closest_hit(r));
    const bool agree = same(n, grid.closest_hit(r, none, filter)) && same(n, grid2.closest_hit(r, none, filter)) &&
                       same(n, grid2.closest_hit(r, counting, filter)) && n_any == grid.any_hit(r, none, filter) &&
                       n_any == grid2.any_hit(r, none, filter) && n_any == grid2.any_hit(r, counting, filter) &&
                       (!reference || (same(n, reference->closest_hit(r)) &&
                                                                 n_any == reference->any_hit(r)));
    if (!agree && ++mismatches <= 3)
      ADD_FAILURE() << "ray o=(" << r.o.x << "," << r.o.y << "," << r.o.z << ") d=(" << r.d.x << "," << r.d.y << ","
                    << r.d.z << ") tmax=" << r.tmax << ": naive " << (n ? int(n->triangle) : -1);
  }
  EXPECT_EQ(mismatches, 0u);
}

TEST(HitFilter, EveryExactAcceleratorReturnsNaivesHitWithTheSameFilter) {
  for (const char* name : {"soup", "bunny"}) {
    SCOPED_TRACE(name);
    const std::vector<Triangle> tris = std::string(name) == "soup"
                                           ? random_soup(2000, 11, 0.2f)
                                           : load_mesh(assets_dir() / "bunny-lowres" / "bunny_lowres.obj");
    ASSERT_GT(tris.size(), 1000u);
    // One triangle in three is a hole.
    std::vector<bool> refused(tris.size());
    std::vector<Triangle> holes_removed = tris;
    for (std::size_t i = 0; i < tris.size(); i += 3) {
      refused[i] = true;
      holes_removed[i] = Triangle{tris[i].v0, tris[i].v0, tris[i].v0};  // unusable: never hit
    }
    const RefuseIds by_id{&refused};
    std::size_t changed = 0;
    expect_all_agree(tris, by_id, &holes_removed, changed);
    EXPECT_GT(changed, 50u) << "the filter changed too few hits to test anything";
    EXPECT_GT(by_id.calls, 0u);
    std::size_t changed_half = 0;
    expect_all_agree(tris, RefuseHalf{}, nullptr, changed_half);
    EXPECT_GT(changed_half, 50u);
  }
}

/// What a scalar loop over `leaves` (in the walk's order) asks the filter:
/// each leaf's list in order, a mailbox like the walk's, stopping where an
/// any-hit walk stops.
template <GridWalk Mode>
std::vector<std::pair<TriangleId, std::uint32_t>> scalar_calls(const std::vector<Triangle>& tris, const NestedGrid& grid2,
                                                               const Ray& r, const std::vector<std::uint64_t>& leaves,
                                                               const std::vector<bool>& refused) {
  const CallLog log{&refused, {}};
  const PreparedRay prepared(r);
  detail::Mailbox mailbox;
  Hit best;
  best.t = r.tmax;
  for (const std::uint64_t leaf : leaves)
    for (const TriangleId id : grid2.leaf(leaf)) {
      if (mailbox.seen(id)) continue;
      if constexpr (Mode == GridWalk::any) {
        if (test_any(prepared, tris[id], id, r.tmin, r.tmax, log)) return log.calls;
      } else {
        test_closest(prepared, tris[id], id, r.tmin, best, log);
      }
    }
  return log.calls;
}

TEST(HitFilter, Grid2AsksTheFilterWhatTheScalarLoopAsksFourAtATimeAndWithARecorder) {
  const std::vector<Triangle> tris = random_soup(3000, 13, 0.3f);
  std::vector<bool> refused(tris.size());
  for (std::size_t i = 0; i < tris.size(); i += 3) refused[i] = true;
  Grid2Options options;
  options.top_density = 0.05;  // leaves of several triangles: batches of four and their tails
  options.leaf_density = 0.5;
  const NestedGrid grid2(tris, options);
  std::size_t calls = 0, rays = 0, mismatches = 0;
  for (const Ray& r : ray_families(tris, grid2, 200, 3)) {
    LeafRecorder closest_leaves, any_leaves;
    const CallLog closest{&refused, {}}, closest_counted{&refused, {}}, any{&refused, {}}, any_counted{&refused, {}};
    NoRecorder none;
    grid2.closest_hit(r, none, closest);
    grid2.closest_hit(r, closest_leaves, closest_counted);
    grid2.any_hit(r, none, any);
    grid2.any_hit(r, any_leaves, any_counted);
    const auto scalar_closest = scalar_calls<GridWalk::closest>(tris, grid2, r, closest_leaves.leaves, refused);
    const auto scalar_any = scalar_calls<GridWalk::any>(tris, grid2, r, any_leaves.leaves, refused);
    const bool agree = closest.calls == scalar_closest && closest_counted.calls == scalar_closest &&
                       any.calls == scalar_any && any_counted.calls == scalar_any;
    if (!agree && ++mismatches <= 3)
      ADD_FAILURE() << "ray o=(" << r.o.x << "," << r.o.y << "," << r.o.z << ") d=(" << r.d.x << "," << r.d.y << ","
                    << r.d.z << "): the filter was asked " << closest.calls.size() << " / " << any.calls.size()
                    << " times, the scalar loop " << scalar_closest.size() << " / " << scalar_any.size();
    calls += scalar_closest.size() + scalar_any.size();
    ++rays;
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_GT(calls, rays);  // most rays asked the filter something
}

TEST(HitFilter, WithoutAFilterTheWalksAnswerAsBefore) {
  const std::vector<Triangle> tris = random_soup(1000, 5, 0.2f);
  const UniformGrid grid(tris, GridOptions{});
  const NestedGrid grid2(tris, Grid2Options{});
  NoRecorder none;
  for (const Ray& r : ray_families(tris, grid, 100, 3)) {
    EXPECT_TRUE(same(grid.closest_hit(r), grid.closest_hit(r, none, NoHitFilter{})));
    EXPECT_TRUE(same(grid2.closest_hit(r), grid2.closest_hit(r, none, NoHitFilter{})));
    EXPECT_EQ(grid2.any_hit(r), grid2.any_hit(r, none, NoHitFilter{}));
  }
}

}  // namespace
}  // namespace kappa::test
