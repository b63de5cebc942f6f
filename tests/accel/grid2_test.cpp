// grid2's own cases: its leaves tile its box and hold what they should, its
// walk reports every leaf it crosses once and in order, its levels refine
// where the triangles are, and its bounds refuse what would explode.
// Its agreement with naive is the suite over every exact accelerator
// (exact_agreement_test.cpp).
#include "accel/grid2.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <random>
#include <set>

#include "accel/dispatch.h"
#include "accel/factory.h"
#include "accel/grid2_traverse.h"
#include "accel/triangle_box.h"
#include "agreement.h"
#include "core/input_error.h"
#include "stats/synthetic_rays.h"
#include "test_util.h"

namespace kappa {
namespace {

NestedGrid make_grid2(std::span<const Triangle> tris, double top = kDefaultGrid2TopDensity,
                        double leaf = kDefaultGrid2LeafDensity) {
  Grid2Options options;
  options.top_density = top;
  options.leaf_density = leaf;
  return NestedGrid(tris, options);
}

/// A dense sphere of `rings` x 2 rings triangles in a corner of an open box
/// 40 times its size: the case a uniform grid loses.
std::vector<Triangle> small_sphere_in_a_large_box(int rings) {
  Scene scene;
  test::add_sphere(scene, {2, 2, 2}, 1.0f, rings, 2 * rings, false, 0);
  test::add_box(scene, {0, 0, 0}, {40, 40, 40}, true, 0);
  return scene.triangles;
}

TEST(Grid2, LeavesTileTheBoxAndHoldTheirOccupancy) {
  const auto tris = small_sphere_in_a_large_box(24);
  const NestedGrid grid = make_grid2(tris);
  const CellLayout& cells = *grid.cells();
  const Grid2Info& info = grid.info();
  ASSERT_EQ(cells.cell_count(), info.leaves);
  const auto theta = cells.occupancies();
  std::uint64_t total = 0, level_cells[kMaxGrid2Levels] = {}, level_theta[kMaxGrid2Levels] = {};
  double volume = 0;
  for (std::uint64_t i = 0; i < cells.cell_count(); ++i) {
    EXPECT_EQ(theta[i], grid.leaf(i).size());
    total += theta[i];
    const int level = cells.cell_level(i);
    ASSERT_TRUE(level >= 0 && level < info.levels) << level;
    ++level_cells[level];
    level_theta[level] += theta[i];
    const CellBox b = cells.cell_box(i);
    const Vec3d e = b.hi - b.lo;
    volume += e.x * e.y * e.z;
  }
  EXPECT_EQ(total, info.theta_tot);
  ASSERT_EQ(cells.levels().size(), std::size_t(info.levels));
  std::uint64_t bytes = 0;
  for (int level = 0; level < info.levels; ++level) {
    EXPECT_EQ(info.level[level].N_c, level_cells[level]);
    EXPECT_EQ(info.level[level].theta_tot, level_theta[level]);
    EXPECT_EQ(cells.levels()[std::size_t(level)].N_c, level_cells[level]);
    bytes += info.level[level].bytes;
  }
  EXPECT_GT(level_cells[0], 0u);  // the box's inside is mostly empty top cells
  EXPECT_GT(level_cells[1], level_cells[0]);  // the sphere's top cells are split finely
  const Vec3d e = cells.bounds().hi - cells.bounds().lo;
  EXPECT_NEAR(volume, e.x * e.y * e.z, 1e-9 * e.x * e.y * e.z);
  EXPECT_EQ(bytes, info.bytes);
  EXPECT_FALSE(cells.uniform_cell_size());
}

TEST(Grid2, LeafListsMatchABruteForceOverlapTestInEveryLeaf) {
  const auto tris = test::random_soup(400, 7, 0.2f);
  for (const auto& [top, leaf] : std::vector<std::pair<double, double>>{{1.0 / 8, 4}, {1e-6, 8}, {1, 2}}) {
    const NestedGrid grid = make_grid2(tris, top, leaf);
    const double m = grid.info().top.margin;
    const Vec3d margin{m, m, m};
    std::uint64_t empty = 0;
    for (std::uint64_t i = 0; i < grid.cell_count(); ++i) {
      const CellBox b = grid.cell_box(i);
      std::vector<TriangleId> expected;
      for (TriangleId id = 0; id < TriangleId(tris.size()); ++id)
        if (triangle_overlaps_box(Vec3d(tris[id].v0), Vec3d(tris[id].v1), Vec3d(tris[id].v2), b.lo - margin,
                                  b.hi + margin))
          expected.push_back(id);
      const auto list = grid.leaf(i);
      ASSERT_EQ(std::vector<TriangleId>(list.begin(), list.end()), expected) << "leaf " << i;
      empty += expected.empty();
    }
    EXPECT_EQ(grid.info().empty_leaves, empty);
  }
}

/// Records the leaves a walk reports.
struct LeafRecorder {
  struct Visit {
    std::uint64_t index;
    int level;
    CellBox box;
  };
  std::vector<Visit> cells;
  std::uint64_t tests = 0;
  WalkCounts counts;
  template <class BoxFn>
  void cell(std::uint64_t index, int level, BoxFn&& box) {
    cells.push_back({index, level, box()});
  }
  void test() { ++tests; }
  void hit() {}
  void finish(const WalkCounts& c, const WalkSegment&) { counts = c; }
};

/// Two leaves are neighbours when they touch on one axis and their extents
/// overlap on the other two (leaves of different sizes meet at a top-cell face).
bool neighbours(const CellBox& a, const CellBox& b) {
  int touching = 0, overlapping = 0;
  for (int k = 0; k < 3; ++k) {
    const double tol = 1e-9 * (1.0 + std::abs(a.hi[k]) + std::abs(b.hi[k]));
    if (std::abs(a.hi[k] - b.lo[k]) < tol || std::abs(b.hi[k] - a.lo[k]) < tol) ++touching;
    else if (std::min(a.hi[k], b.hi[k]) - std::max(a.lo[k], b.lo[k]) > -tol) ++overlapping;
  }
  return touching >= 1 && touching + overlapping == 3;
}

TEST(Grid2, WalkReportsEveryLeafItsSegmentCrossesOnceInOrder) {
  const auto tris = small_sphere_in_a_large_box(12);
  const NestedGrid grid = make_grid2(tris, 1.0 / 4, 8);
  const CellLayout& cells = *grid.cells();
  const CellBox bounds = cells.bounds();
  std::vector<Ray> rays = uniform_lines(bounds.lo, bounds.hi, 200, 3);
  // And segments through the sphere's corner, starting and ending inside.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 5.0);
  for (int k = 0; k < 200; ++k) {
    const Vec3d a{u(rng), u(rng), u(rng)}, b{u(rng) * 4, u(rng) * 4, u(rng) * 4};
    if (length(b - a) > 1e-3) rays.push_back(Ray{Vec3f(a), Vec3f(normalize(b - a)), 0.0f, float(length(b - a))});
  }
  std::size_t walked = 0, through_level1 = 0;
  for (const Ray& ray : rays) {
    LeafRecorder rec;
    grid.walk_whole(ray, rec);
    const Vec3d o(ray.o), d(ray.d);
    const auto chord = clip_to_box(o, d, bounds.lo, bounds.hi, double(ray.tmin), double(ray.tmax));
    std::set<std::uint64_t> expected, reported;
    if (chord)
      for (std::uint64_t i = 0; i < cells.cell_count(); ++i) {
        const CellBox b = cells.cell_box(i);
        if (const auto part = clip_to_box(o, d, b.lo, b.hi, chord->first, chord->second); part && part->second > part->first)
          expected.insert(i);
      }
    bool level1 = false;
    for (const auto& v : rec.cells) {
      ASSERT_TRUE(reported.insert(v.index).second) << "leaf " << v.index << " reported twice";
      EXPECT_EQ(v.level, cells.cell_level(v.index));
      level1 = level1 || v.level == 1;
      const CellBox b = cells.cell_box(v.index);
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(v.box.lo[k], b.lo[k], 1e-12 * (1 + std::abs(b.lo[k])));
        EXPECT_NEAR(v.box.hi[k], b.hi[k], 1e-12 * (1 + std::abs(b.hi[k])));
      }
    }
    for (std::uint64_t c : expected) EXPECT_TRUE(reported.count(c)) << "crossed leaf " << c << " not reported";
    EXPECT_LE(reported.size(), expected.size() + 4);  // a grazing ray may also report leaves it only touches
    for (std::size_t k = 1; k < rec.cells.size(); ++k)
      EXPECT_TRUE(neighbours(rec.cells[k - 1].box, rec.cells[k].box)) << "step " << k << " is not to a neighbour";
    if (!rec.cells.empty()) {
      EXPECT_EQ(rec.counts.cells, rec.cells.size()) << "the walk's count is the leaves it reported";
      ++walked;
    }
    through_level1 += level1;
    if (testing::Test::HasFailure()) return;
  }
  EXPECT_GT(walked, 300u);
  EXPECT_GT(through_level1, 100u);
}

TEST(Grid2, EmptySpaceIsCrossedOneTopCellAtATime) {
  // A ray through the empty middle of the box, far from the sphere: its
  // walk visits top cells only, at most one per top plane it crosses.
  const auto tris = small_sphere_in_a_large_box(48);
  const NestedGrid grid = make_grid2(tris);
  const GridResolution& top = grid.info().top.resolution;
  LeafRecorder rec;
  grid.walk_whole(Ray{{20, 0.5f, 20.5f}, {0, 1, 0}}, rec);
  ASSERT_FALSE(rec.cells.empty());
  std::uint64_t level0 = 0;
  for (const auto& v : rec.cells) level0 += v.level == 0;
  EXPECT_LE(rec.cells.size(), std::uint64_t(top.ny) + 2) << top.to_string();
  // The walls it starts and ends in are sub-grids; everything between is empty.
  EXPECT_GE(level0 + 4, rec.cells.size()) << top.to_string();
  // The sphere's top cells are split into many leaves.
  EXPECT_GT(grid.info().level[1].N_c + grid.info().level[2].N_c, 8 * grid.info().refined) << grid.resolution_text();
}

TEST(Grid2, ASmallDenseObjectInALargeBoxIsRefinedUntilRaysTestFewTriangles) {
  // A sphere of radius 0.05 and 4,608 triangles in an open box of side 20
  // (the teapot in a stadium): it fits in one top cell, and in a few cells
  // of that cell's sub-grid, which the deeper levels refine again.
  Scene scene;
  test::add_sphere(scene, {10, 10, 10}, 0.05f, 48, 96, false, 0);
  test::add_box(scene, {0, 0, 0}, {20, 20, 20}, true, 0);
  const NestedGrid grid = make_grid2(scene.triangles);
  EXPECT_GE(grid.info().levels, 3) << grid.resolution_text();
  std::mt19937 rng(9);
  std::normal_distribution<float> n;
  std::uniform_real_distribution<float> u(-0.04f, 0.04f);
  std::uint64_t tests = 0, hits = 0;
  const int rays = 500;
  for (int k = 0; k < rays; ++k) {
    // From a random point of the box's inside towards the sphere's middle.
    const Vec3f from{10 + 9 * std::tanh(n(rng)), 10 + 9 * std::tanh(n(rng)), 10 + 9 * std::tanh(n(rng))};
    const Vec3f to{10 + u(rng), 10 + u(rng), 10 + u(rng)};
    LeafRecorder rec;
    hits += grid.closest_hit(Ray{from, to - from}, rec).has_value();
    tests += rec.tests;
  }
  EXPECT_EQ(hits, std::uint64_t(rays));
  // Two levels alone leave the sphere in a few cells of 4,608 / 8 triangles and more.
  EXPECT_LT(double(tests) / rays, 60.0) << grid.resolution_text();
  test::expect_agreement(scene.triangles, grid, test::ray_families(scene.triangles, grid, 100, 4));
}

TEST(Grid2, CopiesOfOneLargeTriangleStayBounded) {
  // 10^4 copies of one triangle spanning its box: every top cell and leaf
  // would hold all of them. The top grid is bounded as the uniform grid's
  // is, and each sub-grid is lowered while eq 19 predicts an explosion.
  const Triangle big{{-1, -1, -1}, {1, -1, 1}, {0, 1, 0}};
  const std::vector<Triangle> copies(10000, big);
  const NestedGrid grid = make_grid2(copies);
  const Grid2Info& info = grid.info();
  EXPECT_LT(double(info.theta_tot), 40.0 * 10000 + double(info.leaves)) << grid.resolution_text();
  test::expect_agreement(copies, grid, test::ray_families(copies, grid, 30, 3));
}

TEST(Grid2, MemoryLimitIsAClearError) {
  const auto tris = test::random_soup(2000, 23);
  Grid2Options options;
  options.max_bytes = 4096;
  try {
    NestedGrid grid(tris, options);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--grid-max-bytes"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("grid2"), std::string::npos) << e.what();
  }
}

TEST(Grid2, TheWalkCountsEachSubGridItEnters) {
  // A soup whose top cells each hold a few dozen triangles: most are refined
  // once and their sub-grids' cells hold few, so the leaves are of levels 0
  // and 1 and a sub-grid is known by its top cell. A walk enters one each
  // time it steps from a leaf outside a top cell's sub-grid into one inside.
  const auto tris = test::random_soup(3000, 41);
  const NestedGrid grid = make_grid2(tris, 1.0 / 32, 1);
  const GridInfo& top = grid.info().top;
  const CellBox bounds = grid.cells()->bounds();
  std::uint64_t descents = 0, level1_leaves = 0;
  for (const Ray& ray : uniform_lines(bounds.lo, bounds.hi, 300, 17)) {
    LeafRecorder rec;
    grid.walk_whole(ray, rec);
    std::uint64_t entered = 0;
    std::int64_t in_top_cell = -1;  // the top cell whose sub-grid the walk is in, or -1
    for (const auto& v : rec.cells) {
      ASSERT_LE(v.level, 1) << "the case needs leaves of levels 0 and 1 only";
      if (v.level == 0) {
        in_top_cell = -1;
        continue;
      }
      ++level1_leaves;
      std::int64_t index = 0, stride = 1;
      for (int a = 0; a < 3; ++a) {
        const double centre = 0.5 * (v.box.lo[a] + v.box.hi[a]);
        index += stride * std::int64_t(std::floor((centre - top.lo[a]) / top.cell_size[a]));
        stride *= top.resolution[a];
      }
      if (index != in_top_cell) ++entered, in_top_cell = index;
    }
    EXPECT_EQ(rec.counts.descents, entered);
    descents += rec.counts.descents;
  }
  EXPECT_GT(descents, 300u);  // most lines cross several refined top cells
  EXPECT_GT(level1_leaves, 2 * descents);
  // The uniform grid has no sub-grids.
  GridOptions options;
  options.resolution = GridResolution{20, 20, 20};
  const UniformGrid uniform(tris, options);
  for (const Ray& ray : uniform_lines(bounds.lo, bounds.hi, 20, 3)) {
    LeafRecorder rec;
    uniform.count_closest_walk(ray, std::nullopt, rec);
    EXPECT_EQ(rec.counts.descents, 0u);
  }
}

TEST(Grid2, IsVisitedAsItsOwnTypeAndReportsItsLevels) {
  static_assert(CellWalker<NestedGrid>);
  const auto tris = test::random_soup(300, 29);
  const auto accel = make_accelerator("grid2", tris);
  const bool own_type = visit_accelerator(*accel, [](const auto& a) {
    return std::is_same_v<std::decay_t<decltype(a)>, NestedGrid>;
  });
  EXPECT_TRUE(own_type);
  ASSERT_NE(accel->cells(), nullptr);
  const nlohmann::ordered_json j = accel->report_section();
  ASSERT_GE(j["levels"].size(), 2u);
  std::uint64_t leaves = 0, theta = 0, bytes = 0;
  for (const auto& level : j["levels"]) {
    leaves += level["N_c"].get<std::uint64_t>();
    theta += level["theta_tot"].get<std::uint64_t>();
    bytes += level["bytes"].get<std::uint64_t>();
  }
  EXPECT_EQ(leaves, j["N_c"].get<std::uint64_t>());
  EXPECT_EQ(theta, j["theta_tot"].get<std::uint64_t>());
  EXPECT_EQ(bytes, j["bytes"].get<std::uint64_t>());
  // The options reach it from the command line's settings.
  AccelOptions build;
  build.grid2_top_density = 1e-6;
  const auto one_top = make_accelerator("grid2", tris, build);
  EXPECT_EQ(static_cast<const NestedGrid&>(*one_top).info().top.resolution.cells(), 1u);
}

}  // namespace
}  // namespace kappa
