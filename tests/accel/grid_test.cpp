// The uniform grid's own cases: fixed resolutions at their extremes, its
// lists and occupancy against their definitions, its bounds and refusals.
// Its agreement with naive at default settings is the suite over every exact
// accelerator (exact_agreement_test.cpp).
#include "accel/grid.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <limits>
#include <random>

#include "accel/naive.h"
#include "accel/triangle_box.h"
#include "agreement.h"
#include "core/input_error.h"
#include "renderer/scene/obj/obj_loader.h"
#include "test_util.h"

namespace kappa {
namespace {

using test::expect_agreement;
using test::Rays;

UniformGrid make_grid(std::span<const Triangle> tris, std::optional<GridResolution> res = std::nullopt) {
  GridOptions options;
  options.resolution = res;
  return UniformGrid(tris, options);
}

/// agreement.h's ray families, from the grid's own cell planes.
Rays ray_families(const UniformGrid& grid, std::size_t per_family, std::uint32_t seed) {
  return test::ray_families({}, grid, per_family, seed);
}

TEST(Grid, LowResolutionBunny) {
  const auto tris = test::load_mesh(test::assets_dir() / "bunny-lowres" / "bunny_lowres.obj");
  ASSERT_EQ(tris.size(), 3674u);
  // Fixed resolutions; the auto one is in the suite over every exact accelerator.
  for (auto res : {std::optional<GridResolution>{{1, 1, 1}}, std::optional<GridResolution>{{1, 1, 512}},
                   std::optional<GridResolution>{{37, 5, 64}}}) {
    const UniformGrid grid = make_grid(tris, res);
    SCOPED_TRACE(grid.info().resolution.to_string());
    expect_agreement(tris, grid, ray_families(grid, 150, 12));
  }
}

TEST(Grid, OneTriangleAndFlatScenesOnAFixedGrid) {
  const std::vector<Triangle> one = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};  // flat in z
  const std::vector<Triangle> quad = {{{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}}, {{-1, 0, -1}, {1, 0, 1}, {-1, 0, 1}}};
  std::vector<Triangle> line;  // zero extent in y and z: triangles standing on the x axis
  for (int i = 0; i < 50; ++i) line.push_back({{float(i), 0, 0}, {float(i) + 1, 0, 0}, {float(i) + 0.5f, 0, 0}});
  // Degenerate triangles are left out of the grid; add real ones on the same line for something to hit.
  for (int i = 0; i < 50; ++i) line.push_back({{float(i), 0, 0}, {float(i) + 1, 0, 0}, {float(i) + 0.5f, 1e-3f, 0}});
  for (const std::vector<Triangle>* tris : {&one, &quad, static_cast<const std::vector<Triangle>*>(&line)}) {
    for (auto res : {std::optional<GridResolution>{{8, 8, 8}}}) {  // auto: exact_agreement_test.cpp
      const UniformGrid grid = make_grid(*tris, res);
      SCOPED_TRACE(std::to_string(tris->size()) + " triangles, grid " + grid.info().resolution.to_string());
      expect_agreement(*tris, grid, ray_families(grid, 300, 14));
    }
  }
}

TEST(Grid, DegenerateTrianglesAreLeftOutAndCounted) {
  auto tris = test::random_soup(300, 17, 0.2f);
  tris.push_back({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}});  // collinear
  tris.push_back({{0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}, {0, 1, 0}});  // repeated vertex
  tris.push_back({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}});
  const UniformGrid grid = make_grid(tris);
  EXPECT_EQ(grid.info().degenerate, 3u);
  EXPECT_EQ(grid.info().N, 300u);
  expect_agreement(tris, grid, ray_families(grid, 200, 18));
}

TEST(Grid, LargeCubicResolutionOnASmallScene) {
  const auto tris = test::random_soup(50, 19, 0.3f);
  const UniformGrid grid = make_grid(tris, GridResolution{512, 512, 512});
  EXPECT_EQ(grid.info().resolution.cells(), 512u * 512u * 512u);
  expect_agreement(tris, grid, ray_families(grid, 100, 20));
}

TEST(Grid, WallsOnTheBoundingBoxStayInTheirCells) {
  // A closed box: every wall lies exactly on a face of the grid's box. Rays
  // from inside must all hit, at every resolution (a ceiling that vanished
  // through rounding would let them escape).
  Scene room;
  test::add_box(room, {0, 0, 0}, {556, 548.8f, 559.2f}, true, 0);
  for (auto res : {GridResolution{1, 1, 1}, GridResolution{3, 7, 5}, GridResolution{64, 64, 64}}) {
    const UniformGrid grid = make_grid(room.triangles, res);
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::normal_distribution<float> n;
    for (int i = 0; i < 20000; ++i) {
      const Vec3f o{u(rng) * 556, u(rng) * 548.8f, u(rng) * 559.2f};
      ASSERT_TRUE(grid.closest_hit(Ray{o, {n(rng), n(rng), n(rng)}})) << res.to_string();
    }
    expect_agreement(room.triangles, grid, ray_families(grid, 300, 22));
  }
}

TEST(Grid, OccupancyCountsEveryTriangleInEveryCellItTouches) {
  // A small triangle lying exactly in the plane x = 1 of a 2x2x2 grid over
  // [0,2]^3, with y and z in [0.1, 0.4]: it touches the closed boxes of the
  // two cells on either side of x = 1 at y, z < 1, and no other.
  const std::vector<Triangle> tris = {{{0, 0, 0}, {2, 0, 0}, {0, 2, 2}},   // spans the box diagonal
                                      {{1, 0.1f, 0.1f}, {1, 0.4f, 0.1f}, {1, 0.1f, 0.4f}}};  // on the plane x = 1
  const UniformGrid grid = make_grid(tris, GridResolution{2, 2, 2});
  std::size_t cells_with_second = 0;
  for (std::uint64_t c = 0; c < 8; ++c)
    for (TriangleId id : grid.cell(c)) cells_with_second += id == 1;
  EXPECT_EQ(cells_with_second, 2u);  // cells (0,0,0) and (1,0,0), both closed at x = 1
  // Theta_tot against the definition, not against the offsets it is summed
  // from: the cells each triangle's closed (margin-inflated) box test finds.
  const GridInfo& g = grid.info();
  std::uint64_t expected = 0;
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x) {
        const Vec3d lo = g.lo + Vec3d{double(x), double(y), double(z)} * g.cell_size;
        const Vec3d m{g.margin, g.margin, g.margin};
        for (const Triangle& t : tris)
          expected += triangle_overlaps_box(Vec3d(t.v0), Vec3d(t.v1), Vec3d(t.v2), lo - m, lo + g.cell_size + m);
      }
  EXPECT_EQ(expected, 8u + 2u);  // the diagonal one, in the plane y = z through the centre (1,1,1), touches all 8
  EXPECT_EQ(g.theta_tot, expected);
}

TEST(Grid, CellListsMatchABruteForceOverlapTestInEveryCell) {
  // The stored lists (offsets into the id array, and the occupancy bit the
  // walk reads first) against the definition of a cell's contents: the
  // triangles overlapping its closed box inflated by the margin. 9,361 cells
  // span 147 occupancy words, the last one partial.
  const std::vector<Triangle> tris = test::random_soup(300, 7, 0.2f);
  const UniformGrid grid = make_grid(tris, GridResolution{37, 23, 11});
  const GridInfo& g = grid.info();
  std::uint64_t empty = 0, total = 0;
  for (int z = 0; z < 11; ++z)
    for (int y = 0; y < 23; ++y)
      for (int x = 0; x < 37; ++x) {
        const Vec3d lo{g.lo.x + x * g.cell_size.x, g.lo.y + y * g.cell_size.y, g.lo.z + z * g.cell_size.z};
        const Vec3d hi{x + 1 == 37 ? g.hi.x : lo.x + g.cell_size.x, y + 1 == 23 ? g.hi.y : lo.y + g.cell_size.y,
                       z + 1 == 11 ? g.hi.z : lo.z + g.cell_size.z};
        const Vec3d m{g.margin, g.margin, g.margin};
        std::vector<TriangleId> expected;
        for (TriangleId id = 0; id < TriangleId(tris.size()); ++id)
          if (triangle_overlaps_box(Vec3d(tris[id].v0), Vec3d(tris[id].v1), Vec3d(tris[id].v2), lo - m, hi + m))
            expected.push_back(id);
        const auto cell = grid.cell(grid.cell_index(x, y, z));
        ASSERT_EQ(std::vector<TriangleId>(cell.begin(), cell.end()), expected) << "cell " << x << "," << y << "," << z;
        empty += expected.empty();
        total += expected.size();
      }
  EXPECT_EQ(g.empty_cells, empty);
  EXPECT_EQ(g.theta_tot, total);
  EXPECT_GT(empty, 0u);
  EXPECT_LT(empty, 37u * 23 * 11);
}

TEST(Grid, ResolutionParsingAndChoice) {
  EXPECT_FALSE(parse_grid_resolution("auto"));
  EXPECT_EQ(*parse_grid_resolution("64"), (GridResolution{64, 64, 64}));
  EXPECT_EQ(*parse_grid_resolution("64x32x16"), (GridResolution{64, 32, 16}));
  for (const char* bad : {"", "0", "-4", "64x32", "64x32x16x2", "abc", "4x4xq", "99999"})
    EXPECT_THROW(parse_grid_resolution(bad), InputError) << bad;
  // Near-cubic cells: a 4:2:1 box with 8000 target cells.
  const GridResolution r = choose_resolution({4, 2, 1}, 8000);
  EXPECT_NEAR(double(r.cells()), 8000.0, 8000.0 * 0.3);
  EXPECT_NEAR(4.0 / r.nx, 1.0 / r.nz, 0.3 / r.nz);
  // Flat and line-like boxes: one cell across the missing dimensions.
  const GridResolution flat = choose_resolution({10, 1e-9, 10}, 400);
  EXPECT_EQ(flat.ny, 1);
  EXPECT_EQ(flat.nx, 20);
  const GridResolution line = choose_resolution({10, 1e-9, 1e-9}, 50);
  EXPECT_EQ(line, (GridResolution{50, 1, 1}));
}

// The choice by all 100 bisection steps, as it was before it stopped early:
// the early stop must give the same resolution for every box and target.
GridResolution choose_resolution_by_every_step(const Vec3d& extent, double target_cells) {
  const double largest = max_component(extent);
  if (!(largest > 0) || !(target_cells > 1)) return {};
  auto resolution_for = [&](double cell) {
    GridResolution r;
    int* axes[3] = {&r.nx, &r.ny, &r.nz};
    for (int a = 0; a < 3; ++a) *axes[a] = int(std::clamp(std::round(extent[a] / cell), 1.0, double(kMaxGridAxis)));
    return r;
  };
  double small = largest / kMaxGridAxis, big = largest;
  for (int i = 0; i < 100; ++i) {
    const double mid = std::sqrt(small * big);
    if (double(resolution_for(mid).cells()) > target_cells) small = mid;
    else big = mid;
  }
  const GridResolution a = resolution_for(small), b = resolution_for(big);
  const double da = std::abs(std::log(double(a.cells()) / target_cells));
  const double db = std::abs(std::log(double(b.cells()) / target_cells));
  return da < db ? a : b;
}

TEST(Grid, ResolutionChoiceStopsEarlyWithTheSameAnswer) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> log_extent(-3, 3), log_target(0.1, 9);
  int compared = 0;
  for (int i = 0; i < 20000; ++i) {
    Vec3d extent{std::pow(10.0, log_extent(rng)), std::pow(10.0, log_extent(rng)), std::pow(10.0, log_extent(rng))};
    if (i % 4 == 1) extent.y = extent.x;            // two axes' steps coincide
    if (i % 4 == 2) extent = {extent.x, extent.x, extent.x};
    if (i % 8 == 3) extent.z = 1e-9 * extent.x;     // flat
    const double target = std::pow(10.0, log_target(rng));
    ASSERT_EQ(choose_resolution(extent, target), choose_resolution_by_every_step(extent, target))
        << extent.x << " " << extent.y << " " << extent.z << " target " << target;
    ++compared;
  }
  // The targets past kMaxGridAxis^3 and below 1 as well.
  for (double target : {0.5, 1.0, 1.0000001, 2.0, 1e13, 1e15})
    EXPECT_EQ(choose_resolution({1, 2, 3}, target), choose_resolution_by_every_step({1, 2, 3}, target)) << target;
  EXPECT_EQ(compared, 20000);
}

TEST(Grid, MemoryLimitIsAClearError) {
  const auto tris = test::random_soup(10, 23);
  GridOptions options;
  options.resolution = GridResolution{1024, 1024, 1024};
  options.max_bytes = 1 << 20;
  try {
    UniformGrid grid(tris, options);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--grid-max-bytes"), std::string::npos) << e.what();
  }
}

TEST(Grid, AutoResolutionBoundsThetaForCopiesOfOneLargeTriangle) {
  // 10^4 copies of one triangle spanning its box: at lambda = 32 (3.2e5 cells)
  // each copy would sit in thousands of cells. The bound lowers N_c before
  // anything is allocated.
  const Triangle big{{-1, -1, -1}, {1, -1, 1}, {0, 1, 0}};
  const std::vector<Triangle> copies(10000, big);
  const UniformGrid grid(copies, GridOptions{});
  const GridInfo& info = grid.info();
  const double bound = kThetaBoundPerTriangle * 10000 + double(info.resolution.cells());
  EXPECT_LE(double(info.theta_tot), 1.5 * bound) << info.resolution.to_string();  // eq 19 predicts it within rounding
  EXPECT_LT(info.resolution.cells(), 1000u) << info.resolution.to_string();
  EXPECT_GT(info.resolution.cells(), 1u) << info.resolution.to_string();
  // An explicit resolution is taken as given (the user asked for it).
  GridOptions explicit_res;
  explicit_res.resolution = GridResolution{20, 20, 20};
  EXPECT_EQ(UniformGrid(std::span(copies).first(10), explicit_res).info().resolution, (GridResolution{20, 20, 20}));
  // Eq 19's sums given by a chooser that made them are the ones the bound
  // reads: the copies' own give the grid they give unasked (lowered), a small
  // soup's (never over the bound) leave lambda * N cells.
  const std::span<const Triangle> hundred = std::span(copies).first(100);
  const GridInfo unasked = UniformGrid(hundred, GridOptions{}).info();
  EXPECT_LT(unasked.resolution.cells(), std::uint64_t(kDefaultGridDensity * 100)) << unasked.resolution.to_string();
  const OccupancyModel own(hundred);
  GridOptions given;
  given.occupancy = &own;
  EXPECT_EQ(UniformGrid(hundred, given).info().resolution, unasked.resolution);
  const OccupancyModel small(test::random_soup(100, 5, 0.01f));
  given.occupancy = &small;
  EXPECT_EQ(UniformGrid(hundred, given).info().resolution,
            choose_resolution(unasked.hi - unasked.lo, kDefaultGridDensity * 100.0));
}

TEST(Grid, ThetaBoundLeavesRealScenesAtLambdaTimesN) {
  for (const auto& obj : {test::assets_dir() / "bunny-lowres" / "bunny_lowres.obj"}) {
    const std::vector<Triangle> mesh = test::load_mesh(obj);
    const UniformGrid grid(mesh, GridOptions{});
    const Vec3d extent = grid.info().hi - grid.info().lo;
    EXPECT_EQ(grid.info().resolution, choose_resolution(extent, kDefaultGridDensity * double(mesh.size()))) << obj;
  }
}

TEST(Grid, OccupancyModelIsEq19SummedTriangleByTriangle) {
  const std::vector<Triangle> soup = test::random_soup(500, 3, 0.2f);
  const OccupancyModel model(soup);
  EXPECT_EQ(model.N, 500.0);
  const Vec3d l{0.1, 0.05, 0.2};
  double expected = 0;  // eq 19 per triangle: 1 + sum_a L_a / l_a + sum_{a<b} A_ab / (l_a l_b)
  for (const Triangle& t : soup) {
    const Vec3d a(t.v0), b(t.v1), c(t.v2);
    const Vec3d L = max(a, max(b, c)) - min(a, min(b, c));
    const Vec3d A = abs(cross(b - a, c - a)) * 0.5;
    expected += 1 + L.x / l.x + L.y / l.y + L.z / l.z + A.x / (l.y * l.z) + A.y / (l.x * l.z) + A.z / (l.x * l.y);
  }
  EXPECT_NEAR(model.theta_tot(l), expected, 1e-9 * expected);
  // Within the bound, bounded_resolution changes nothing; far outside, it lowers N_c until within.
  const Vec3d extent{2, 2, 2};
  EXPECT_EQ(bounded_resolution(model, extent, GridResolution{8, 8, 8}), (GridResolution{8, 8, 8}));
  const std::vector<Triangle> copies(1000, Triangle{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0.5f}});
  const OccupancyModel big(copies);
  const GridResolution lowered = bounded_resolution(big, extent, GridResolution{64, 64, 64});
  const Vec3d cell{2.0 / lowered.nx, 2.0 / lowered.ny, 2.0 / lowered.nz};
  EXPECT_LE(big.theta_tot(cell), kThetaBoundPerTriangle * 1000 + double(lowered.cells())) << lowered.to_string();
  const Vec3d before{2.0 / 64, 2.0 / 64, 2.0 / 64};
  EXPECT_GT(big.theta_tot(before), kThetaBoundPerTriangle * 1000 + 64.0 * 64 * 64);  // it was outside
  EXPECT_LT(lowered.cells(), 64u * 64u * 64u);
}

}  // namespace
}  // namespace kappa

namespace kappa {
namespace {

TEST(Grid, RaysThroughSharedMeshVerticesPickTheSameTriangleAsNaive) {
  // Rays aimed exactly at mesh vertices meet several triangles at (nearly)
  // equal t: the tie rule must decide, not the order in which the grid
  // happens to test them. Shuffled ids put higher ids in earlier cells.
  Scene sphere;
  test::add_sphere(sphere, {0, 0, 0}, 1.0f, 10, 20, false, 0);
  std::vector<Triangle> tris = sphere.triangles;
  std::mt19937 rng(31);
  std::shuffle(tris.begin(), tris.end(), rng);
  std::uint32_t seed = 33;
  for (auto res : {GridResolution{4, 4, 4}, GridResolution{16, 16, 16}, GridResolution{33, 7, 19}}) {
    const UniformGrid grid = make_grid(tris, res);
    SCOPED_TRACE(res.to_string());
    expect_agreement(tris, grid, test::rays_at_vertices(tris, 6000, seed++));
  }
}

// The entry cell of a ray from a far origin, into a grid of thin cells: the
// walk widens its start by a margin that grows with |origin|, and at 1e12 the
// entry point lies some 6e10 cells outside the grid, which overflowed an int
// before being clamped (undefined behaviour; the sanitizer build flags it).
// Release builds happened to agree with naive anyway: the float triangle test
// cannot resolve hits from that far (its rounding bound exceeds t), so both
// miss there; nearer origins hit, and every answer must equal naive's.
TEST(Grid, FarOriginsIntoThinCellsEnterTheRightCell) {
  const auto tris = test::random_soup(400, 41, 0.2f);  // in [-1, 1]^3
  const UniformGrid along_x = make_grid(tris, GridResolution{kMaxGridAxis, 4, 4});
  const UniformGrid along_y = make_grid(tris, GridResolution{4, kMaxGridAxis, 4});
  // The case is the one it names: the start margin, in cells, exceeds an int.
  const double margin_cells = kMarginUlps * double(FLT_EPSILON) * 1e12 / along_x.info().cell_size.x;
  EXPECT_GT(margin_cells, double(std::numeric_limits<int>::max()));
  Rays x_rays, y_rays;
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(-0.8f, 0.8f);
  for (float far : {1e2f, 1e4f, 1e9f, 1e12f}) {
    for (int k = 0; k < 50; ++k) {
      const float a = u(rng), b = u(rng);
      x_rays.push_back(Ray{{far, a, b}, {-1, 0, 0}});  // entering through the high x face
      x_rays.push_back(Ray{{-far, a, b}, {1, 0, 0}});  // and the low one
      y_rays.push_back(Ray{{a, far, b}, {0, -1, 0}});
      y_rays.push_back(Ray{{a, -far, b}, {0, 1, 0}});
    }
  }
  expect_agreement(tris, along_x, x_rays);
  expect_agreement(tris, along_y, y_rays);
  const NaiveAccelerator naive(tris);
  std::size_t hits = 0;
  for (const Ray& r : x_rays) hits += naive.closest_hit(r).has_value();
  EXPECT_GT(hits, 50u);  // the nearer rays do meet the soup
}

}  // namespace
}  // namespace kappa
