// The cost model's resolution chooser (--grid-res model) with constants fixed
// here: its 2 % rule, its counting walks against a cast's counts, and its
// search against a brute force over every candidate. No timing.
#include "stats/resolution_choice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <ranges>
#include <limits>
#include <random>

#include "accel/grid_traverse.h"
#include "accel/naive.h"
#include "core/input_error.h"
#include "stats/cast.h"
#include "test_util.h"

namespace kappa {
namespace {

Candidate candidate(int side, double total) {
  Candidate c;
  c.res = GridResolution{side, side, side};
  c.traversal_s = total;
  return c;
}

TEST(ResolutionChoice, SmallestWithinTakesTheFewestCellsNearTheMinimum) {
  // A flat curve: 16^3 is cheapest, 8^3 within 2 % of it, 4^3 not.
  const std::vector<Candidate> flat = {candidate(16, 1.00), candidate(8, 1.015), candidate(4, 1.03), candidate(32, 1.01)};
  EXPECT_EQ(smallest_within(flat), 1u);
  EXPECT_EQ(smallest_within(flat, 0.0), 0u);   // no tolerance: the minimum itself
  EXPECT_EQ(smallest_within(flat, 0.05), 2u);  // 5 %: 4^3 too
  // A steep curve: only the minimum.
  const std::vector<Candidate> steep = {candidate(4, 2.0), candidate(8, 1.5), candidate(16, 1.0), candidate(32, 1.3)};
  EXPECT_EQ(smallest_within(steep), 2u);
}

/// The search on a cost curve given as numbers: which indices it evaluates.
std::vector<std::size_t> searched(const std::vector<double>& costs, std::size_t start, double tolerance = 0.02) {
  std::vector<std::size_t> seen;
  search_unimodal(costs.size(), start, [&](std::size_t i) {
    if (std::find(seen.begin(), seen.end(), i) == seen.end()) seen.push_back(i);
    return costs[i];
  }, tolerance);
  std::sort(seen.begin(), seen.end());
  return seen;
}

TEST(ResolutionChoice, TheSearchWalksDownhillThenBelowTheMinimumWhileWithinTheTolerance) {
  const double inf = std::numeric_limits<double>::infinity();
  // Flat below the minimum (index 4): 3 and 2 are within 2 %, 1 is not; the search must reach 2.
  const std::vector<double> flat = {1.2, 1.03, 1.015, 1.01, 1.0, 1.2, 1.5};
  EXPECT_EQ(searched(flat, 5), (std::vector<std::size_t>{1, 2, 3, 4, 5, 6}));
  // Uphill from the start: never past the first rise, nothing evaluated beyond it.
  const std::vector<double> steep = {5, 4, 3, 2, 1, 2, 3, 4};
  EXPECT_EQ(searched(steep, 1), (std::vector<std::size_t>{1, 2, 3, 4, 5}));
  EXPECT_EQ(searched(steep, 6), (std::vector<std::size_t>{3, 4, 5, 6, 7}));
  // The start over the budget: down until one fits, then as usual.
  const std::vector<double> budget = {3, 2, 1.5, inf, inf};
  EXPECT_EQ(searched(budget, 4), (std::vector<std::size_t>{1, 2, 3, 4}));
  // What it evaluated holds the choice over all: the smallest index within 2 % of the least.
  std::vector<Candidate> all, seen;
  for (std::size_t i = 0; i < flat.size(); ++i) all.push_back(candidate(int(i) + 2, flat[i]));
  for (std::size_t i : searched(flat, 5)) seen.push_back(all[i]);
  EXPECT_EQ(seen[smallest_within(seen)].res, all[smallest_within(all)].res);
  EXPECT_EQ(all[smallest_within(all)].res, (GridResolution{4, 4, 4}));
}

/// A scene whose best resolution is not the default's: a dense small cluster
/// in a large sparse box (the paper's teapot in a stadium, in miniature).
std::vector<Triangle> cluster_in_a_box() {
  std::vector<Triangle> tris = test::random_soup(4000, 7, 0.01f);
  for (Triangle& t : tris)
    for (Vec3f* v : {&t.v0, &t.v1, &t.v2}) *v = *v * 0.1f;  // a cluster 0.2 across
  const std::vector<Triangle> sparse = test::random_soup(200, 8, 0.2f);
  for (const Triangle& t : sparse) tris.push_back({t.v0 * 5.0f, t.v1 * 5.0f, t.v2 * 5.0f});  // a box 10 across
  return tris;
}

/// Rays from the box's edge towards the cluster, with their closest hits from naive.
std::vector<PilotSegment> segments_for(std::span<const Triangle> tris, int n) {
  const NaiveAccelerator naive(tris);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<PilotSegment> segments;
  for (int i = 0; i < n; ++i) {
    const Vec3f o{5 * u(rng), 5 * u(rng), -5.5f};
    const Vec3f target{0.2f * u(rng), 0.2f * u(rng), 0.2f * u(rng)};
    Ray ray{o, target - o};
    const auto hit = naive.closest_hit(ray);
    segments.push_back({ray, hit ? hit->t : ray.tmax, hit.has_value(), i % 2 ? kCamera : kBounce2});
  }
  return segments;
}

/// Constants fixed for the test: a cost per cell, per occupied cell and per
/// test, no cache terms; a build cost per triangle, reference and cell.
struct FixedModels {
  TimeModel traversal = extended_model(1e12);
  BuildModel build;
  FixedModels() {
    const auto set = [&](const std::string& term, double ns) {
      for (std::size_t i = 0; i < traversal.terms.size(); ++i)
        if (traversal.terms[i] == term) traversal.ns[i] = ns;
    };
    set("T0_camera", 30);
    set("T0_bounce2", 60);
    set("Ts", 3);
    set("Ts_occupied", 20);
    set("Th", 6);
    build.ns = {20, 60, 2};
    build.threads = 1;
  }
  ChoiceSettings settings(double scale) const {
    ChoiceSettings s;
    s.traversal = &traversal;
    s.build = &build;
    s.rays_scale.fill(scale);
    s.threads = 1;
    s.max_bytes = std::uint64_t(1) << 32;
    return s;
  }
};

TEST(ResolutionChoice, CountingWalksGiveACastsCountsOnTheSameRays) {
  const std::vector<Triangle> tris = cluster_in_a_box();
  const std::vector<PilotSegment> segments = segments_for(tris, 3000);
  GridOptions options;
  options.resolution = GridResolution{40, 40, 40};
  const UniformGrid grid(tris, options);
  std::vector<Ray> rays;
  for (const PilotSegment& s : segments) rays.push_back(s.ray);
  const CastMeasurement cast = cast_with_counters(grid, rays, GridWalk::closest);
  const auto loads = count_segments(grid, segments);
  double cells = 0, tests = 0, skips = 0, hits = 0, rays_counted = 0;
  for (const QueryLoad& l : loads) {
    cells += l.cells, tests += l.tests, skips += l.skips, hits += l.hits, rays_counted += l.rays;
    EXPECT_EQ(l.working_set_bytes, double(grid.bytes() + tris.size() * sizeof(Triangle)));
  }
  EXPECT_EQ(rays_counted, 3000.0);
  EXPECT_EQ(cells, double(cast.counters.totals.cells));
  EXPECT_EQ(tests, double(cast.counters.totals.tests));
  EXPECT_EQ(skips, double(cast.counters.totals.mailbox_skips));
  EXPECT_EQ(hits, double(cast.counters.totals.hits));
  EXPECT_EQ(loads[kCamera].rays, 1500.0);
  EXPECT_EQ(loads[kBounce2].rays, 1500.0);
}

TEST(ResolutionChoice, TheSearchFindsTheBruteForceChoiceOverEveryResolution) {
  const std::vector<Triangle> tris = cluster_in_a_box();
  const std::vector<PilotSegment> segments = segments_for(tris, 2000);
  const FixedModels models;
  for (const double scale : {10.0, 1000.0, 100000.0}) {  // few rays: the build weighs; many: the walk does
    const ChoiceSettings settings = models.settings(scale);
    // Brute force, independently of the chooser's bookkeeping: every candidate built and predicted.
    const OccupancyModel occupancy(tris);
    std::vector<Candidate> all;
    for (const GridResolution& r : candidate_resolutions(tris))
      all.push_back(evaluate_candidate(*counting_grid(tris, r, segments, settings.max_bytes), segments, settings, &occupancy));
    ASSERT_GT(all.size(), 10u);
    const GridResolution best = all[smallest_within(all)].res;
    const ResolutionChoice searched = choose_resolution_by_model(tris, segments, settings);
    const ResolutionChoice exhaustive = choose_resolution_by_model(tris, segments, settings, true);
    EXPECT_EQ(exhaustive.evaluated[exhaustive.chosen].res, best) << scale;
    EXPECT_EQ(searched.evaluated[searched.chosen].res, best) << scale;
    ASSERT_TRUE(searched.grid);
    EXPECT_EQ(searched.grid->info().resolution, best) << scale;  // the chosen candidate's whole grid
    EXPECT_FALSE(searched.grid->info().partial);
    EXPECT_LT(searched.evaluated.size(), all.size()) << scale;   // the search skipped some
    EXPECT_EQ(exhaustive.evaluated.size(), all.size()) << scale;
  }
  // More rays favour more cells: the choice at 10^5 paths per pilot path has at least the cells of the one at 10.
  const auto cells_at = [&](double scale) {
    const ResolutionChoice c = choose_resolution_by_model(tris, segments, models.settings(scale));
    return c.evaluated[c.chosen].res.cells();
  };
  EXPECT_GT(cells_at(100000.0), cells_at(10.0));
}

TEST(ResolutionChoice, ACountingGridCountsTheSegmentsAsTheWholeGridDoesWithFewerReferences) {
  const std::vector<Triangle> tris = cluster_in_a_box();
  const std::vector<PilotSegment> segments = segments_for(tris, 1500);
  const OccupancyModel occupancy(tris);
  for (const int side : {6, 23, 64}) {
    SCOPED_TRACE(side);
    const GridResolution res{side, side, side};
    GridOptions options;
    options.resolution = res;
    const UniformGrid whole(tris, options);
    const auto partial = counting_grid(tris, res, segments, options.max_bytes);
    EXPECT_TRUE(partial->info().partial);
    EXPECT_FALSE(whole.info().partial);
    // Every visited cell holds the whole grid's list; the others are empty.
    const std::vector<std::uint64_t> visited = visited_cells(whole, segments);
    EXPECT_EQ(visited_cells(*partial, segments), visited);
    std::uint64_t visited_refs = 0, cells_visited = 0;
    for (std::uint64_t c = 0; c < whole.cell_count(); ++c) {
      const bool v = (visited[c >> 6] >> (c & 63)) & 1;
      cells_visited += v;
      if (v) {
        visited_refs += whole.cell(c).size();
        ASSERT_TRUE(std::ranges::equal(partial->cell(c), whole.cell(c)))
            << c << ": " << partial->cell(c).size() << " of " << whole.cell(c).size();
      } else {
        ASSERT_TRUE(partial->cell(c).empty()) << c;
      }
    }
    EXPECT_GT(cells_visited, 0u);
    EXPECT_LT(cells_visited, whole.cell_count());
    EXPECT_EQ(partial->info().theta_tot, visited_refs);
    EXPECT_LT(partial->info().theta_tot, whole.info().theta_tot);
    // Its counts are the whole grid's, with the whole grid's working set.
    const auto a = count_segments(whole, segments);
    const auto b = count_segments(*partial, segments, double(whole.info().theta_tot));
    for (std::size_t k = 0; k < kRenderClasses; ++k) {
      EXPECT_EQ(a[k].cells, b[k].cells);
      EXPECT_EQ(a[k].occupied, b[k].occupied);
      EXPECT_EQ(a[k].tests, b[k].tests);
      EXPECT_EQ(a[k].skips, b[k].skips);
      EXPECT_EQ(a[k].working_set_bytes, b[k].working_set_bytes);
      EXPECT_EQ(a[k].list_bytes, b[k].list_bytes);
    }
    // Its candidate's Theta_tot is eq 19's for the whole grid; the whole grid's candidate, its own.
    const FixedModels models;
    const Candidate predicted = evaluate_candidate(*partial, segments, models.settings(1), &occupancy);
    EXPECT_EQ(predicted.theta_tot, std::uint64_t(std::llround(occupancy.theta_tot(whole.info().cell_size))));
    EXPECT_EQ(evaluate_candidate(whole, segments, models.settings(1)).theta_tot, whole.info().theta_tot);
    EXPECT_NEAR(double(predicted.theta_tot), double(whole.info().theta_tot), 0.5 * double(whole.info().theta_tot));
  }
}

TEST(ResolutionChoice, ThePilotsWholeGridIsReusedWhenItsResolutionIsChosen) {
  const std::vector<Triangle> tris = cluster_in_a_box();
  const std::vector<PilotSegment> segments = segments_for(tris, 1000);
  const FixedModels models;
  const ChoiceSettings settings = models.settings(1000.0);
  const ResolutionChoice free_choice = choose_resolution_by_model(tris, segments, settings);
  GridOptions options;
  options.resolution = free_choice.evaluated[free_choice.chosen].res;
  const UniformGrid whole(tris, options);
  const ResolutionChoice reused = choose_resolution_by_model(tris, segments, settings, false, &whole);
  EXPECT_EQ(reused.evaluated[reused.chosen].res, whole.info().resolution);
  EXPECT_FALSE(reused.grid);  // the caller's grid is the frame's
  EXPECT_EQ(reused.evaluated[reused.chosen].theta_tot, whole.info().theta_tot);  // counted on it, not predicted
}

TEST(ResolutionChoice, CandidatesOverTheMemoryBudgetAreSkippedAndNoneFittingIsAnError) {
  const std::vector<Triangle> tris = cluster_in_a_box();
  const std::vector<PilotSegment> segments = segments_for(tris, 500);
  const FixedModels models;
  ChoiceSettings settings = models.settings(1e6);
  settings.max_bytes = 200000;  // a few thousand cells at most
  const ResolutionChoice c = choose_resolution_by_model(tris, segments, settings);
  EXPECT_LE(c.evaluated[c.chosen].bytes, settings.max_bytes);
  EXPECT_FALSE(c.skipped.empty());
  settings.stats_bytes_per_cell = 40;  // per-cell statistics count against the budget too
  const ResolutionChoice with_stats = choose_resolution_by_model(tris, segments, settings);
  EXPECT_LT(with_stats.evaluated[with_stats.chosen].res.cells(), c.evaluated[c.chosen].res.cells());
  settings.max_bytes = 10;
  EXPECT_THROW(choose_resolution_by_model(tris, segments, settings), InputError);
}

TEST(ResolutionChoice, CandidatesKeepWithinTheThetaBound) {
  const std::vector<Triangle> copies(3000, Triangle{{-1, -1, -1}, {1, -1, 1}, {0, 1, 0}});
  const OccupancyModel occupancy(copies);
  const GridBox box = grid_box(copies);
  for (const GridResolution& r : candidate_resolutions(copies)) {
    const Vec3d cell{box.extent().x / r.nx, box.extent().y / r.ny, box.extent().z / r.nz};
    EXPECT_LE(occupancy.theta_tot(cell), kThetaBoundPerTriangle * 3000 + double(r.cells())) << r.to_string();
  }
}

}  // namespace
}  // namespace kappa
