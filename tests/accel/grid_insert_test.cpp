// Slab-by-slab insertion finds exactly the cells the separating-axis test
// accepts over the triangle's whole bounding box, for triangles chosen to
// hurt it, and its work grows with the cells a triangle touches.
#include "accel/grid_insert.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <random>
#include <vector>

#include "test_util.h"

namespace kappa {
namespace {

Vec3d inverse_cell(const GridInfo& g) { return {1.0 / g.cell_size.x, 1.0 / g.cell_size.y, 1.0 / g.cell_size.z}; }

/// The definition: every cell whose closed box, inflated by the margin, the
/// triangle overlaps.
std::vector<std::uint64_t> brute_force_cells(const GridInfo& g, const Triangle& t) {
  std::vector<std::uint64_t> cells;
  const Vec3d m{g.margin, g.margin, g.margin};
  const GridResolution& r = g.resolution;
  for (int z = 0; z < r.nz; ++z)
    for (int y = 0; y < r.ny; ++y)
      for (int x = 0; x < r.nx; ++x) {
        const Vec3d lo{g.lo.x + x * g.cell_size.x, g.lo.y + y * g.cell_size.y, g.lo.z + z * g.cell_size.z};
        const Vec3d hi{x + 1 == r.nx ? g.hi.x : lo.x + g.cell_size.x, y + 1 == r.ny ? g.hi.y : lo.y + g.cell_size.y,
                       z + 1 == r.nz ? g.hi.z : lo.z + g.cell_size.z};
        if (triangle_overlaps_box(Vec3d(t.v0), Vec3d(t.v1), Vec3d(t.v2), lo - m, hi + m))
          cells.push_back(std::uint64_t(x) + std::uint64_t(r.nx) * (std::uint64_t(y) + std::uint64_t(r.ny) * std::uint64_t(z)));
      }
  return cells;
}

void expect_same_cells(const GridInfo& g, std::span<const Triangle> tris) {
  const Vec3d inv = inverse_cell(g);
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < tris.size(); ++i) {
    std::vector<std::uint64_t> found;
    for_each_overlapped_cell(g, inv, tris[i], [&](std::uint64_t c) { found.push_back(c); });
    const std::vector<std::uint64_t> expected = brute_force_cells(g, tris[i]);
    if (found != expected && ++wrong <= 3) {
      const Triangle& t = tris[i];
      ADD_FAILURE() << "triangle " << i << " (" << t.v0.x << "," << t.v0.y << "," << t.v0.z << ") (" << t.v1.x << ","
                    << t.v1.y << "," << t.v1.z << ") (" << t.v2.x << "," << t.v2.y << "," << t.v2.z << "): "
                    << found.size() << " cells found, " << expected.size() << " overlapped";
    }
  }
  EXPECT_EQ(wrong, 0u);
}

/// Triangles that sit where slab clipping could go wrong: on cell planes, along
/// cell edges and corners, across the whole grid, as needles and slivers, and
/// nearly parallel to a slab. Cells are unit cubes with planes at integers.
std::vector<Triangle> hostile_triangles() {
  std::vector<Triangle> t;
  // In cell planes, inside the box and on its faces.
  t.push_back({{0.5f, 0.5f, 3}, {7.5f, 1.5f, 3}, {2.5f, 6.5f, 3}});
  t.push_back({{1, 5, 1}, {7, 5, 2}, {3, 5, 7}});
  t.push_back({{0, 1, 1}, {0, 7, 2}, {0, 3, 7}});
  t.push_back({{8, 1, 1}, {8, 7, 2}, {8, 3, 7}});
  t.push_back({{1, 1, 8}, {7, 2, 8}, {3, 7, 8}});
  // Edges along grid lines, vertices on grid corners.
  t.push_back({{2, 4, 0}, {2, 4, 8}, {5, 1, 3}});
  t.push_back({{2, 2, 2}, {6, 2, 2}, {2, 6, 2}});
  t.push_back({{1, 1, 1}, {2, 2, 2}, {3, 1, 2}});
  t.push_back({{4, 4, 4}, {5, 4, 4}, {4, 4, 5}});
  // Across the whole grid.
  t.push_back({{0, 0, 0}, {8, 8, 0}, {0, 8, 8}});
  t.push_back({{0, 0, 0}, {8, 8, 8}, {8, 0, 8}});
  t.push_back({{0, 0, 8}, {8, 0, 0}, {4, 8, 4}});
  // Needles and slivers, on and off the planes.
  t.push_back({{0.1f, 0.2f, 0.3f}, {7.9f, 7.8f, 7.7f}, {7.9f, 7.8f, 7.7001f}});
  t.push_back({{0, 3, 3}, {8, 3, 3}, {8, 3.0001f, 3}});
  t.push_back({{3, 0, 5}, {3.0000005f, 8, 5}, {3, 8, 5.0000005f}});
  // Nearly parallel to z planes, just off them, and crossing one by an ulp.
  t.push_back({{0.5f, 0.5f, 4}, {7.5f, 0.5f, 4.0000005f}, {0.5f, 7.5f, 3.9999995f}});
  t.push_back({{0.5f, 0.5f, 2.0000002f}, {7.5f, 0.5f, 2.0000002f}, {0.5f, 7.5f, 2.0000002f}});
  t.push_back({{0.5f, 0.5f, 1.9999999f}, {7.5f, 0.5f, 1.9999999f}, {0.5f, 7.5f, 1.9999999f}});
  // Random large triangles with vertices snapped to the planes, and random ones.
  std::mt19937 rng(19);
  std::uniform_int_distribution<int> grid_point(0, 8);
  std::uniform_real_distribution<float> anywhere(0.0f, 8.0f);
  for (int i = 0; i < 200; ++i) {
    auto snapped = [&] { return Vec3f{float(grid_point(rng)), float(grid_point(rng)), float(grid_point(rng))}; };
    auto loose = [&] { return Vec3f{anywhere(rng), anywhere(rng), anywhere(rng)}; };
    t.push_back({snapped(), snapped(), snapped()});
    t.push_back({loose(), loose(), loose()});
    t.push_back({snapped(), loose(), snapped()});
  }
  std::erase_if(t, [](const Triangle& tri) { return !usable_triangle(tri); });
  return t;
}

UniformGrid unit_cell_grid(std::span<const Triangle> tris, GridResolution res, Vec3d hi) {
  GridOptions options;
  options.resolution = res;
  options.box = std::pair{Vec3d{0, 0, 0}, hi};
  return UniformGrid(tris, options);
}

TEST(GridInsert, SlabsFindExactlyTheCellsTheWholeBoxTestFinds) {
  const std::vector<Triangle> tris = hostile_triangles();
  ASSERT_GT(tris.size(), 600u);
  // Unit cells with planes exactly at the integers the triangles sit on.
  expect_same_cells(unit_cell_grid(tris, GridResolution{8, 8, 8}, {8, 8, 8}).info(), tris);
  // Cells that do not divide evenly, and one slab along an axis.
  expect_same_cells(unit_cell_grid(tris, GridResolution{13, 5, 7}, {8, 8, 8}).info(), tris);
  expect_same_cells(unit_cell_grid(tris, GridResolution{9, 11, 1}, {8, 8, 8}).info(), tris);
  // The grid's own bounds and resolution, and a soup of small triangles.
  GridOptions automatic;
  expect_same_cells(UniformGrid(tris, automatic).info(), tris);
  const std::vector<Triangle> soup = test::random_soup(300, 23, 0.3f);
  expect_same_cells(UniformGrid(soup, automatic).info(), soup);
}

TEST(GridInsert, AFlatSceneInAGridWithManyThinSlabs) {
  // All triangles in z = 1: the box is only the margin thick, yet cut in 16.
  std::vector<Triangle> tris;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> xy(0.0f, 4.0f);
  for (int i = 0; i < 100; ++i) tris.push_back({{xy(rng), xy(rng), 1}, {xy(rng), xy(rng), 1}, {xy(rng), xy(rng), 1}});
  GridOptions options;
  options.resolution = GridResolution{6, 6, 16};
  expect_same_cells(UniformGrid(tris, options).info(), tris);
}

TEST(GridInsert, WorkGrowsWithTheCellsTouchedNotWithTheBoundingBox) {
  // One triangle across a 64^3 grid: its box is every cell, it touches a
  // thin sheet of them. The whole-box search made 262,144 tests.
  const std::vector<Triangle> tris{{{0, 0, 0}, {8, 8, 0}, {0, 8, 8}}};
  const GridInfo g = unit_cell_grid(tris, GridResolution{64, 64, 64}, {8, 8, 8}).info();
  std::uint64_t touched = 0;
  const std::uint64_t tests = for_each_overlapped_cell(g, inverse_cell(g), tris[0], [&](std::uint64_t) { ++touched; });
  EXPECT_GT(touched, 64u * 64);  // a sheet at least one cell thick over 64 x 64
  EXPECT_LT(touched, 64u * 64 * 64 / 10);
  EXPECT_LE(tests, 2 * touched) << touched << " cells touched";
}

TEST(GridInsert, MaxMultiplicityIsTheMostCellsOfOneTriangleAndThetaMaxTheFullestCell) {
  // The paper's multiplicity M_j counts the cells triangle j is in; the
  // fullest cell is another quantity (it was reported under this name).
  const std::vector<Triangle> tris = hostile_triangles();
  const UniformGrid grid = unit_cell_grid(tris, GridResolution{13, 5, 7}, {8, 8, 8});
  const GridInfo& g = grid.info();
  std::uint64_t most = 0;
  std::vector<std::uint32_t> theta(g.resolution.cells(), 0);
  for (const Triangle& t : tris) {
    const std::vector<std::uint64_t> cells = brute_force_cells(g, t);
    most = std::max<std::uint64_t>(most, cells.size());
    for (std::uint64_t c : cells) ++theta[c];
  }
  EXPECT_EQ(g.max_multiplicity, most);
  EXPECT_EQ(g.max_occupancy, *std::max_element(theta.begin(), theta.end()));
  EXPECT_NE(g.max_multiplicity, std::uint64_t(g.max_occupancy));  // the two differ here
  const auto section = grid.report_section();
  EXPECT_EQ(section.at("max_multiplicity").get<std::uint64_t>(), most);
  EXPECT_EQ(section.at("theta_max").get<std::uint64_t>(), g.max_occupancy);
}

}  // namespace
}  // namespace kappa
