// The recorder protocol (accel/recorder.h) as the grid's walk keeps it: every
// cell the walked segment crosses is reported once, in order, with the box
// the CellLayout gives it; the walk's cell count is the number reported; and
// the segment it hands over is the part of the ray it walked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "accel/dispatch.h"
#include "accel/factory.h"
#include "accel/grid.h"
#include "accel/grid_traverse.h"
#include "stats/synthetic_rays.h"
#include "test_util.h"

namespace kappa {
namespace {

struct Visit {
  std::uint64_t index;
  int level;
  CellBox box;
};

/// Records everything the walk reports.
struct ListRecorder {
  std::vector<Visit> cells;
  std::uint64_t tests = 0, hits = 0, finishes = 0;
  WalkCounts counts;
  WalkSegment segment;

  template <class BoxFn>
  void cell(std::uint64_t index, int level, BoxFn&& box) {
    cells.push_back({index, level, box()});
  }
  void test() { ++tests; }
  void hit() { ++hits; }
  void finish(const WalkCounts& c, const WalkSegment& s) {
    ++finishes;
    counts = c;
    segment = s;
  }
};

/// The cells whose boxes the segment o + t d, t in [t0, t1], passes through
/// the inside of (by clipping it against every box: no walk involved).
std::set<std::uint64_t> crossed_cells(const CellLayout& cells, const Vec3d& o, const Vec3d& d, double t0, double t1) {
  std::set<std::uint64_t> crossed;
  for (std::uint64_t i = 0; i < cells.cell_count(); ++i) {
    const CellBox b = cells.cell_box(i);
    if (const auto part = clip_to_box(o, d, b.lo, b.hi, t0, t1); part && part->second > part->first) crossed.insert(i);
  }
  return crossed;
}

bool share_a_face(const CellBox& a, const CellBox& b) {
  int touching = 0, overlapping = 0;
  for (int k = 0; k < 3; ++k) {
    const double tol = 1e-9 * (1.0 + std::abs(a.hi[k]));
    if (std::abs(a.hi[k] - b.lo[k]) < tol || std::abs(b.hi[k] - a.lo[k]) < tol) ++touching;
    else if (std::abs(a.lo[k] - b.lo[k]) < tol && std::abs(a.hi[k] - b.hi[k]) < tol) ++overlapping;
  }
  return touching == 1 && overlapping == 2;
}

TEST(Walk, ReportsEveryCellItsSegmentCrossesOnceInOrder) {
  const auto tris = test::random_soup(300, 21, 0.15f);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.5, 1.5);
  for (const GridResolution res : {GridResolution{7, 5, 3}, GridResolution{16, 16, 16}, GridResolution{1, 9, 2}}) {
    GridOptions options;
    options.resolution = res;
    const UniformGrid grid(tris, options);
    const CellLayout& cells = *grid.cells();
    const CellBox bounds = cells.bounds();
    // Whole chords of uniform lines, and segments that start or end inside the box.
    std::vector<Ray> rays = uniform_lines(bounds.lo, bounds.hi, 150, 3);
    for (int k = 0; k < 150; ++k) {
      const Vec3d a = bounds.lo + Vec3d{u(rng), u(rng), u(rng)} * (bounds.hi - bounds.lo) * 0.5 + (bounds.hi - bounds.lo) * 0.25;
      const Vec3d b = bounds.lo + Vec3d{u(rng), u(rng), u(rng)} * (bounds.hi - bounds.lo);
      const Vec3d d = normalize(b - a);
      rays.push_back(Ray{Vec3f(a), Vec3f(d), 0.0f, float(length(b - a))});
    }
    std::size_t walked = 0;
    for (const Ray& ray : rays) {
      ListRecorder rec;
      grid.walk_whole(ray, rec);
      ASSERT_EQ(rec.finishes, rec.cells.empty() ? rec.finishes : 1u);
      const Vec3d o(ray.o), d(ray.d);
      const auto chord = clip_to_box(o, d, bounds.lo, bounds.hi, double(ray.tmin), double(ray.tmax));
      const std::set<std::uint64_t> expected =
          chord ? crossed_cells(cells, o, d, chord->first, chord->second) : std::set<std::uint64_t>{};
      std::set<std::uint64_t> reported;
      for (const Visit& v : rec.cells) {
        EXPECT_TRUE(reported.insert(v.index).second) << "cell " << v.index << " reported twice";
        EXPECT_EQ(v.level, 0);
        const CellBox b = cells.cell_box(v.index);
        EXPECT_EQ(v.box.lo, b.lo);
        EXPECT_EQ(v.box.hi, b.hi);
      }
      // A grazing ray may also report a cell it only touches; every cell it
      // crosses must be reported.
      for (std::uint64_t c : expected) EXPECT_TRUE(reported.count(c)) << "crossed cell " << c << " not reported";
      EXPECT_LE(reported.size(), expected.size() + 2);
      for (std::size_t k = 1; k < rec.cells.size(); ++k)
        EXPECT_TRUE(share_a_face(rec.cells[k - 1].box, rec.cells[k].box)) << "step " << k << " is not to a neighbour";
      if (!rec.cells.empty()) {
        EXPECT_EQ(rec.counts.cells, rec.cells.size()) << "the walk's count is the cells it reported";
        EXPECT_NEAR(rec.segment.t_in, chord->first, 1e-9 * (1 + std::abs(chord->first)));
        EXPECT_NEAR(rec.segment.t_out, chord->second, 1e-9 * (1 + std::abs(chord->second)));
        ++walked;
      }
      if (testing::Test::HasFailure()) return;
    }
    EXPECT_GT(walked, 200u);
  }
}

TEST(Walk, AnAxisRayThroughCellCentresVisitsExactlyOneRowOfCells) {
  // A 4x4x4 grid over [0, 4]^3 (one triangle inside); a ray along x through
  // the centres of the cells at y = 1, z = 2 crosses exactly 4 cells.
  const std::vector<Triangle> tris = {{{1, 1, 1}, {3, 1, 1}, {1, 3, 3}}};
  GridOptions options;
  options.resolution = GridResolution{4, 4, 4};
  options.box = std::pair{Vec3d{0, 0, 0}, Vec3d{4, 4, 4}};
  const UniformGrid grid(tris, options);
  for (const Vec3f d : {Vec3f{1, 0, 0}, Vec3f{-1, 0, 0}}) {
    ListRecorder rec;
    grid.walk_whole(Ray{{d.x > 0 ? -1.0f : 5.0f, 1.5f, 2.5f}, d}, rec);
    ASSERT_EQ(rec.cells.size(), 4u);
    EXPECT_EQ(rec.counts.cells, 4u);
    for (int k = 0; k < 4; ++k)
      EXPECT_EQ(rec.cells[std::size_t(k)].index, grid.cell_index(d.x > 0 ? k : 3 - k, 1, 2)) << k;
  }
}

TEST(Walk, SegmentsWithEndsAwayFromCellPlanesCrossExactlyTheirCells) {
  // Ends farther than the insertion margin from every cell plane: the walk
  // reports exactly the cells whose interior the segment crosses, no more.
  const auto tris = test::random_soup(200, 25, 0.2f);
  GridOptions options;
  options.resolution = GridResolution{9, 7, 5};
  const UniformGrid grid(tris, options);
  const GridInfo& g = grid.info();
  const CellLayout& cells = *grid.cells();
  std::mt19937 rng(26);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto away_from_planes = [&](const Vec3d& p) {
    for (int a = 0; a < 3; ++a) {
      const double f = (p[a] - g.lo[a]) / g.cell_size[a];
      if (std::abs(f - std::round(f)) * g.cell_size[a] < 100 * g.margin) return false;
    }
    return true;
  };
  int checked = 0;
  while (checked < 300) {
    const Vec3d a = g.lo + Vec3d{u(rng), u(rng), u(rng)} * (g.hi - g.lo);
    const Vec3d b = g.lo + Vec3d{u(rng), u(rng), u(rng)} * (g.hi - g.lo);
    if (!away_from_planes(a) || !away_from_planes(b)) continue;
    const Vec3d d = normalize(b - a);
    const Ray ray{Vec3f(a), Vec3f(d), 0.0f, float(length(b - a))};
    const Vec3d o(ray.o), dd(ray.d);  // as the walk sees them, in float
    ListRecorder rec;
    grid.walk_whole(ray, rec);
    std::set<std::uint64_t> reported;
    for (const Visit& v : rec.cells) reported.insert(v.index);
    const std::set<std::uint64_t> expected = crossed_cells(cells, o, dd, 0.0, double(ray.tmax));
    ASSERT_EQ(reported, expected) << "segment " << checked;
    ASSERT_EQ(rec.counts.cells, expected.size());
    ++checked;
  }
}

TEST(Walk, ClosestHitWalksReportTheCellsUpToTheirHitAndItsTests) {
  const auto tris = test::random_soup(400, 22, 0.1f);
  GridOptions options;
  options.resolution = GridResolution{10, 10, 10};
  const UniformGrid grid(tris, options);
  const CellBox bounds = grid.cells()->bounds();
  std::size_t hit_rays = 0;
  for (const Ray& ray : uniform_lines(bounds.lo, bounds.hi, 1500, 8)) {
    ListRecorder rec;
    const auto hit = grid.closest_hit(ray, rec);
    EXPECT_EQ(hit.has_value(), grid.closest_hit(ray).has_value());
    EXPECT_EQ(rec.counts.tests, rec.tests);
    if (!hit) continue;
    ++hit_rays;
    EXPECT_GE(rec.hits, 1u);
    EXPECT_EQ(rec.segment.t_end, double(hit->t));
    // Every cell the ray crosses before its hit was walked.
    const Vec3d o(ray.o), d(ray.d);
    const auto before =
        crossed_cells(*grid.cells(), o, d, std::max(rec.segment.t_in, 0.0), double(hit->t) * (1 - 1e-6));
    std::set<std::uint64_t> reported;
    for (const Visit& v : rec.cells) reported.insert(v.index);
    for (std::uint64_t c : before) EXPECT_TRUE(reported.count(c)) << "cell " << c << " before the hit not reported";
    EXPECT_EQ(rec.counts.cells, rec.cells.size());
  }
  EXPECT_GT(hit_rays, 100u);
}

TEST(Dispatch, TheGridIsVisitedAsItsOwnTypeTheOthersThroughTheInterface) {
  const auto tris = test::random_soup(50, 23);
  static_assert(CellWalker<UniformGrid>);
  static_assert(!CellWalker<Accelerator>);
  for (const char* name : {"grid", "naive", "embree"}) {
    const auto accel = make_accelerator(name, tris);
    const bool as_grid = visit_accelerator(*accel, [](const auto& a) {
      return std::is_same_v<std::decay_t<decltype(a)>, UniformGrid>;
    });
    EXPECT_EQ(as_grid, std::string(name) == "grid") << name;
    EXPECT_EQ(accel->cells() != nullptr, std::string(name) == "grid") << name;
    EXPECT_GE(accel->build_s(), 0.0);
  }
}

TEST(CellLayout, TheGridsCellsTileItsBoxAndHoldItsOccupancy) {
  const auto tris = test::random_soup(200, 24);
  GridOptions options;
  options.resolution = GridResolution{6, 4, 5};
  const UniformGrid grid(tris, options);
  const CellLayout& cells = *grid.cells();
  ASSERT_EQ(cells.cell_count(), 120u);
  const auto theta = cells.occupancies();
  std::uint64_t total = 0;
  double volume = 0;
  for (std::uint64_t i = 0; i < cells.cell_count(); ++i) {
    total += theta[i];
    EXPECT_EQ(theta[i], grid.cell(i).size());
    const CellBox b = cells.cell_box(i);
    const Vec3d e = b.hi - b.lo;
    volume += e.x * e.y * e.z;
    EXPECT_EQ(cells.cell_level(i), 0);
  }
  EXPECT_EQ(total, grid.info().theta_tot);
  const Vec3d e = cells.bounds().hi - cells.bounds().lo;
  EXPECT_NEAR(volume, e.x * e.y * e.z, 1e-9 * e.x * e.y * e.z);
  EXPECT_EQ(cells.cell_box(0).lo, cells.bounds().lo);
  EXPECT_EQ(cells.resolution_text(), "6x4x5");
}

TEST(Walk, CountingWalkWithAKnownHitReportsTheClosestWalksCellsAndTests) {
  // What the resolution chooser counts on a candidate from a pilot's hits:
  // the same cells, lists and mailboxed tests as the walk that tests
  // triangles, at resolutions from coarse to fine.
  const std::vector<Triangle> soup = test::random_soup(3000, 11, 0.08f);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.5f, 1.5f);
  for (const GridResolution res : {GridResolution{4, 4, 4}, GridResolution{23, 17, 31}, GridResolution{96, 96, 96}}) {
    GridOptions options;
    options.resolution = res;
    const UniformGrid grid(soup, options);
    std::uint64_t hits = 0;
    for (int i = 0; i < 2000; ++i) {
      Ray ray{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
      if (i % 3 == 0) ray.tmax = 0.5f;  // some end before any hit
      ListRecorder real, counted;
      const std::optional<Hit> hit = grid.closest_hit(ray, real);
      hits += hit.has_value();
      grid.count_closest_walk(ray, hit ? std::optional<float>(hit->t) : std::nullopt, counted);
      ASSERT_EQ(counted.finishes, real.finishes);
      EXPECT_EQ(counted.counts.cells, real.counts.cells) << res.to_string() << " ray " << i;
      EXPECT_EQ(counted.counts.occupied, real.counts.occupied) << res.to_string() << " ray " << i;
      EXPECT_EQ(counted.counts.refs, real.counts.refs) << res.to_string() << " ray " << i;
      EXPECT_EQ(counted.counts.tests, real.counts.tests) << res.to_string() << " ray " << i;
      EXPECT_EQ(counted.counts.skips, real.counts.skips) << res.to_string() << " ray " << i;
      EXPECT_EQ(counted.tests, real.tests);
      EXPECT_EQ(counted.cells.size(), real.cells.size());
      EXPECT_EQ(counted.segment.t_end, real.segment.t_end);
      EXPECT_EQ(counted.hits, 0u);  // nothing is tested
    }
    EXPECT_GT(hits, 200u) << res.to_string();  // the rays hit often enough to test the stop
  }
}

}  // namespace
}  // namespace kappa
