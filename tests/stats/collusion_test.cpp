// kappa and its ingredients against hand computations, and the paper's
// identities measured on real casts.
#include "stats/collusion.h"

#include <gtest/gtest.h>
#include <tbb/info.h>

#include <cstdio>
#include <numeric>
#include <random>
#include <thread>

#include "accel/grid.h"
#include "accel/grid_traverse.h"
#include "core/thread_limit.h"
#include "renderer/scene/obj/obj_loader.h"
#include "stats/cast.h"
#include "stats/cost_model.h"
#include "stats/synthetic_rays.h"
#include "test_util.h"

namespace kappa {
namespace {

TEST(Collusion, HandComputedKappa) {
  // 4 cells, 10 rays: p = (0.5, 0.1, 0.2, 0.2), Theta = (3, 0, 1, 0).
  const std::vector<std::uint64_t> visits = {5, 1, 2, 2};
  const std::vector<std::uint32_t> theta = {3, 0, 1, 0};
  const CollusionStats s = collusion(visits, theta, 10);
  EXPECT_DOUBLE_EQ(s.p_tot, 1.0);
  EXPECT_DOUBLE_EQ(s.p_avg, 0.25);
  EXPECT_DOUBLE_EQ(s.theta_tot, 4.0);
  EXPECT_DOUBLE_EQ(s.theta_avg, 1.0);
  // eq 8: N_c sum p_i Theta_i / (p_tot Theta_tot) = 4 * (1.5 + 0.2) / 4 = 1.7
  ASSERT_TRUE(s.kappa);
  EXPECT_NEAR(*s.kappa, 1.7, 1e-12);
  EXPECT_NEAR(s.refs_per_ray, 1.7, 1e-12);
  // The corrected eq 25 agrees to rounding.
  ASSERT_TRUE(s.kappa_eq25);
  EXPECT_NEAR(*s.kappa_eq25, *s.kappa, 1e-12);
  ASSERT_TRUE(s.r);
  EXPECT_GT(*s.r, 0.0);
}

TEST(Collusion, UniformCellsGiveKappaOneAndNoCorrelation) {
  const std::vector<std::uint64_t> visits = {4, 4, 4};
  const std::vector<std::uint32_t> theta = {0, 5, 1};
  const CollusionStats s = collusion(visits, theta, 8);
  EXPECT_NEAR(*s.kappa, 1.0, 1e-15);
  EXPECT_EQ(*s.kappa_eq25, 1.0);
  EXPECT_FALSE(s.r);  // sigma_p = 0: undefined, reported as null
}

TEST(Collusion, EmptyInputsAreUndefinedNotNaN) {
  const std::vector<std::uint64_t> visits = {0, 0};
  const std::vector<std::uint32_t> theta = {1, 2};
  const CollusionStats none = collusion(visits, theta, 0);
  EXPECT_FALSE(none.kappa);
  EXPECT_FALSE(none.kappa_eq25);
  EXPECT_EQ(none.p_tot, 0.0);
  const CollusionStats no_cells = collusion({}, {}, 5);
  EXPECT_FALSE(no_cells.kappa);
}

TEST(CostModel, Eq19ForAnAxisAlignedTriangleByHand) {
  // Right triangle in the z = 0 plane with legs 2 (x) and 1 (y), cells 1 x 1 x 1:
  // 1 + Lx + Ly + Lz + A_yz + A_xz + A_xy = 1 + 2 + 1 + 0 + 0 + 0 + 1 = 5.
  const std::vector<Triangle> t = {{{0, 0, 0}, {2, 0, 0}, {0, 1, 0}}};
  EXPECT_DOUBLE_EQ(theta_tot_eq19(t, {1, 1, 1}), 5.0);
  // Non-cubic cells scale each term by its own sides.
  EXPECT_DOUBLE_EQ(theta_tot_eq19(t, {2, 0.5, 4}), 1.0 + 1.0 + 2.0 + 0.0 + 1.0 / (2 * 0.5));
}

TEST(CostModel, Eq22ReducesToEq23ForCubicCells) {
  // eq 23: p_tot = 6 V^(2/3) N_c^(1/3) / SA(V) for cubes of side l = (V/N_c)^(1/3).
  const Vec3d box{4, 2, 3};
  const double N_c = 24 * 8 * 8 * 8;  // cells of side 1/8... V = 24
  const double l = std::cbrt(24.0 / N_c);
  const double sa = 2 * (4 * 2 + 2 * 3 + 3 * 4);
  EXPECT_NEAR(p_tot_lines_eq22(box, {l, l, l}, N_c), 6 * std::pow(24.0, 2.0 / 3.0) * std::cbrt(N_c) / sa, 1e-9);
}

// --- the model's identities, measured ---------------------------------------

UniformGrid grid_at(std::span<const Triangle> tris, GridResolution res) {
  GridOptions o;
  o.resolution = res;
  return UniformGrid(tris, o);
}

TEST(CastIdentities, UniformLinesHaveKappaOneAndPtotOfEq22) {
  const auto random = test::random_soup(3000, 1, 0.05f);
  const auto bunny = test::load_mesh(test::assets_dir() / "bunny-lowres" / "bunny_lowres.obj");
  for (const auto* tris : {&random, &bunny}) {
    for (auto res : {GridResolution{8, 8, 8}, GridResolution{16, 16, 16}, GridResolution{32, 32, 32},
                     GridResolution{64, 64, 64}, GridResolution{40, 10, 25}}) {
      const UniformGrid grid = grid_at(*tris, res);
      const GridInfo& g = grid.info();
      const auto lines = uniform_lines(g.lo, g.hi, 60000, 7);
      const CastMeasurement m = cast_with_counters(grid, lines, GridWalk::whole);
      const double predicted = p_tot_lines_eq22(g.hi - g.lo, g.cell_size, double(res.cells()));
      SCOPED_TRACE(res.to_string() + (tris == &random ? " soup" : " bunny"));
      std::printf("lines %s %-10s: p_tot %.4f eq22 %.4f (ratio %.4f), kappa %.4f, kappa_eq25 %.4f\n",
                  tris == &random ? "soup " : "bunny", res.to_string().c_str(), m.collusion.p_tot, predicted,
                  m.collusion.p_tot / predicted, m.collusion.kappa.value_or(-1), m.collusion.kappa_eq25.value_or(-1));
      EXPECT_NEAR(m.collusion.p_tot / predicted, 1.0, 0.01) << m.collusion.p_tot << " vs " << predicted;
      // The walk's own prediction, chord by chord (both ends on the box:
      // sum_a |v_a| / l_a, no leading 1), agrees with what it walked.
      EXPECT_NEAR(m.cells_per_ray_predicted / m.collusion.p_tot, 1.0, 0.01)
          << m.cells_per_ray_predicted << " vs " << m.collusion.p_tot;
      ASSERT_TRUE(m.collusion.kappa);
      EXPECT_NEAR(*m.collusion.kappa, 1.0, 0.03);
      EXPECT_NEAR(*m.collusion.kappa_eq25, *m.collusion.kappa, 1e-9);
      // Sum of visits over cells = sum of cells over rays.
      std::uint64_t visits = 0;
      for (auto v : m.counters.visits()) visits += v;
      EXPECT_EQ(visits, m.counters.totals.cells);
      EXPECT_EQ(m.counters.totals.rays, lines.size());
    }
  }
}

TEST(CastIdentities, SegmentsCrossOnePlusSumOfLengthOverCellCells) {
  const auto tris = test::random_soup(2000, 2, 0.05f);
  for (auto res : {GridResolution{16, 16, 16}, GridResolution{32, 32, 32}, GridResolution{48, 20, 33}}) {
    const UniformGrid grid = grid_at(tris, res);
    const GridInfo& g = grid.info();
    const double length = 2.0 * (g.cell_size.x + g.cell_size.y + g.cell_size.z) / 3.0;  // two mean cell widths
    const auto segments = uniform_segments(g.lo, g.hi, length, 60000, 3);
    const CastMeasurement m = cast_with_counters(grid, segments, GridWalk::whole);
    // Eq 24 per axis from the segments themselves (wholly inside the box).
    double expected = 0;
    for (const Ray& r : segments) {
      const Vec3d v = Vec3d(r.d) * double(r.tmax - r.tmin);
      expected += 1.0 + std::abs(v.x) / g.cell_size.x + std::abs(v.y) / g.cell_size.y + std::abs(v.z) / g.cell_size.z;
    }
    expected /= double(segments.size());
    SCOPED_TRACE(res.to_string());
    std::printf("segments %-10s: cells per segment %.4f eq24 %.4f (ratio %.4f)\n", res.to_string().c_str(),
                m.collusion.p_tot, expected, m.collusion.p_tot / expected);
    EXPECT_NEAR(m.collusion.p_tot / expected, 1.0, 0.01) << m.collusion.p_tot << " vs " << expected;
    // The walk sums the same prediction (in 1/1024 units).
    EXPECT_NEAR(m.cells_per_ray_predicted, expected, 1e-3);
  }
}

/// Theta_tot of grids of the same cell size shifted by random offsets.
double mean_theta_over_offsets(std::span<const Triangle> tris, const Vec3d& cell, int offsets, std::uint32_t seed) {
  Vec3d lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  for (const Triangle& t : tris)
    for (const Vec3f& v : {t.v0, t.v1, t.v2}) lo = min(lo, Vec3d(v)), hi = max(hi, Vec3d(v));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double sum = 0;
  for (int k = 0; k < offsets; ++k) {
    const Vec3d shift{u(rng) * cell.x, u(rng) * cell.y, u(rng) * cell.z};
    GridOptions o;
    const Vec3d box_lo = lo - shift;
    GridResolution res;
    res.nx = int(std::ceil((hi.x - box_lo.x) / cell.x)) + 1;
    res.ny = int(std::ceil((hi.y - box_lo.y) / cell.y)) + 1;
    res.nz = int(std::ceil((hi.z - box_lo.z) / cell.z)) + 1;
    o.resolution = res;
    o.box = std::make_pair(box_lo, box_lo + Vec3d{res.nx * cell.x, res.ny * cell.y, res.nz * cell.z});
    sum += double(UniformGrid(tris, o).info().theta_tot);
  }
  return sum / offsets;
}

TEST(CastIdentities, ThetaTotOverRandomOffsetsMatchesEq19AndEq21) {
  const auto random = test::random_soup(3000, 4, 0.08f);
  const Vec3d cell{0.1, 0.07, 0.13};
  const double measured = mean_theta_over_offsets(random, cell, 12, 5);
  std::printf("theta_tot soup: measured %.1f eq19 %.1f eq21 %.1f\n", measured, theta_tot_eq19(random, cell),
              theta_tot_eq21(random, cell));
  EXPECT_NEAR(measured / theta_tot_eq19(random, cell), 1.0, 0.02);
  EXPECT_NEAR(measured / theta_tot_eq21(random, cell), 1.0, 0.02);  // random orientation holds for a soup
  const auto bunny = test::load_mesh(test::assets_dir() / "bunny-lowres" / "bunny_lowres.obj");
  const Vec3d bunny_cell{0.4, 0.35, 0.3};
  const double bunny_measured = mean_theta_over_offsets(bunny, bunny_cell, 12, 6);
  std::printf("theta_tot bunny: measured %.1f eq19 %.1f eq21 %.1f\n", bunny_measured, theta_tot_eq19(bunny, bunny_cell),
              theta_tot_eq21(bunny, bunny_cell));
  EXPECT_NEAR(bunny_measured / theta_tot_eq19(bunny, bunny_cell), 1.0, 0.02);
}

TEST(CastIdentities, CountersDoNotDependOnTheThreadCount) {
  const auto tris = test::random_soup(2000, 8, 0.05f);
  const UniformGrid grid = grid_at(tris, {20, 20, 20});
  const auto lines = uniform_lines(grid.info().lo, grid.info().hi, 20000, 9);
  const auto cast_on = [&](int threads) {
    const ThreadLimit limit(threads);
    EXPECT_EQ(active_threads(), std::min(threads, tbb::info::default_concurrency()));
    return cast_with_counters(grid, lines, GridWalk::closest);
  };
  const CastMeasurement one = cast_on(1);
  const CastMeasurement two = cast_on(2);
  EXPECT_EQ(one.counters.visits(), two.counters.visits());
  EXPECT_EQ(one.counters.totals.tests, two.counters.totals.tests);
  EXPECT_EQ(one.counters.totals.mailbox_skips, two.counters.totals.mailbox_skips);
  EXPECT_EQ(one.counters.totals.hits, two.counters.totals.hits);
  EXPECT_EQ(*one.collusion.kappa, *two.collusion.kappa);
}

}  // namespace
}  // namespace kappa

namespace kappa {
namespace {

TEST(Counters, SharedArraysCountWhatOwnArraysCount) {
  // Two threads walking half the lines each into one shared set of arrays
  // (atomic increments) must count per cell exactly what one thread counts
  // into its own; and merging two own sets adds them up.
  const auto tris = test::random_soup(500, 11, 0.05f);
  const UniformGrid grid = grid_at(tris, {12, 12, 12});
  const auto lines = uniform_lines(grid.info().lo, grid.info().hi, 4000, 12);
  CellCounters own(grid.cell_count(), grid.info().cell_size);
  for (const Ray& r : lines) {
    CellCounters::Tally t(own);
    grid.walk_whole(r, t);
  }
  const auto shared = std::make_shared<CellArrays>(grid.info().resolution.cells());
  CellCounters first(shared, grid.info().cell_size), second(shared, grid.info().cell_size);
  const auto walk_half = [&](CellCounters& counters, std::size_t parity) {
    for (std::size_t i = parity; i < lines.size(); i += 2) {
      CellCounters::SharedTally t(counters);
      grid.walk_whole(lines[i], t);
    }
  };
  std::thread other(walk_half, std::ref(second), 1);
  walk_half(first, 0);
  other.join();
  first.merge(second);
  EXPECT_EQ(first.visits(), own.visits());
  EXPECT_EQ(first.per_cell_queries(), own.per_cell_queries());
  EXPECT_EQ(first.totals.cells, own.totals.cells);

  CellCounters sum(grid.cell_count(), grid.info().cell_size);
  sum.merge(own);
  sum.merge(own);
  const auto v = sum.visits(), p = own.visits();
  for (std::size_t i = 0; i < v.size(); ++i) ASSERT_EQ(v[i], 2 * p[i]);
  EXPECT_GT(std::accumulate(p.begin(), p.end(), std::uint64_t(0)), 0u);
}

}  // namespace
}  // namespace kappa
