// Progressive rendering: passes add samples to each pixel in sample order, so
// any passes of a total are bitwise the one-pass image of that total; the
// budgets size and stop the passes (a fake clock stands in for time); a
// non-finite sample is dropped, never averaged in; --adaptive is the same
// image for any thread count.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <vector>

#include "core/thread_limit.h"
#include "renderer/render/pass_planner.h"
#include "renderer/render/pixel_samples.h"
#include "renderer/render/render_helpers.h"
#include "renderer/scene/scene_loader.h"
#include "test_util.h"

namespace kappa {
namespace {

Scene cornell(int size) {
  Warnings warnings;
  Scene scene = load_scene(test::assets_dir() / "cornell-box" / "scene.json", warnings);
  scene.width = scene.height = size;
  return scene;
}

/// A clock the test advances: `per_sample` seconds for every sample per
/// pixel a pass took, whatever the machine does.
struct FakeClock {
  double now = 0;
  double per_sample = 0.01;
  int spp_seen = 0;
  void advance_to(int spp) {
    now += per_sample * (spp - spp_seen);
    spp_seen = spp;
  }
};

struct Rendered {
  Film film;
  RenderResult result;
  std::vector<int> pass_spp;  ///< the total after each pass
};

Rendered render_budgeted(const Scene& scene, const Budget& budget, RenderSettings settings, FakeClock& clock) {
  PassPlanner planner(budget, [&clock] { return clock.now; });
  Rendered out{Film(scene.width, scene.height, settings.aov), {}, {}};
  PassControl control{&planner, nullptr, [&](const FrameState& state, int) {
                        clock.advance_to(state.spp);
                        out.pass_spp.push_back(state.spp);
                      }};
  settings.passes = &control;
  const auto accel = make_accelerator("grid", scene.triangles);
  out.result = render(scene, *accel, settings, out.film);
  return out;
}

TEST(Passes, AStoppedRenderIsBitwiseTheSppImageOfItsTotal) {
  const Scene scene = cornell(24);
  RenderSettings settings;
  settings.seed = 3;
  settings.aov.variance = settings.aov.spp = true;
  settings.aov.albedo = settings.aov.depth = true;
  Budget budget;
  budget.time_s = 1.0;  // 0.01 s a sample: about 100 samples, in passes of 1, 5, 5, ...
  FakeClock clock;
  const Rendered budgeted = render_budgeted(scene, budget, settings, clock);
  ASSERT_GE(budgeted.result.passes, 10);
  EXPECT_EQ(budgeted.result.spp, budgeted.pass_spp.back());
  EXPECT_EQ(budgeted.pass_spp.front(), 1) << "a time budget starts with one sample";
  EXPECT_EQ(budgeted.result.stop_reason, "time-budget");

  settings.spp = budgeted.result.spp;
  const Film one_pass = test::render_scene(scene, settings, "grid");
  EXPECT_TRUE(test::bitwise_equal(budgeted.film.rgb, one_pass.rgb)) << budgeted.result.spp << " spp";
  EXPECT_TRUE(test::bitwise_equal(budgeted.film.variance, one_pass.variance));
  EXPECT_TRUE(test::bitwise_equal(budgeted.film.albedo, one_pass.albedo));
  EXPECT_TRUE(test::bitwise_equal(budgeted.film.depth, one_pass.depth));
  EXPECT_TRUE(test::bitwise_equal(budgeted.film.spp, one_pass.spp));
  EXPECT_EQ(budgeted.film.spp[0], float(budgeted.result.spp));
  // And the total matters: one sample fewer is another image.
  settings.spp -= 1;
  EXPECT_FALSE(test::bitwise_equal(budgeted.film.rgb, test::render_scene(scene, settings, "grid").rgb));
}

// The interrupt of the next test, raised from inside a pass: the test hook
// sees every sample, and once armed it interrupts after 100 more.
std::atomic<bool> g_interrupt{false}, g_armed{false};
std::atomic<int> g_samples_since_armed{0};
bool interrupt_mid_pass(std::uint64_t, std::uint64_t) {
  if (g_armed && g_samples_since_armed.fetch_add(1) == 100) g_interrupt = true;
  return false;
}

TEST(Passes, AnInterruptedRenderIsTheImageOfItsCompletedPasses) {
  const Scene scene = cornell(24);
  RenderSettings settings;
  settings.aov.variance = true;
  settings.test_nonfinite = interrupt_mid_pass;
  Budget budget;
  budget.time_s = 1.0;
  FakeClock clock;
  PassPlanner planner(budget, [&clock] { return clock.now; });
  Film film(scene.width, scene.height, settings.aov);
  // Once three passes are complete, the fourth is interrupted after 100 of
  // its samples: some of its pixels have their samples, others not.
  PassControl control{&planner, &g_interrupt, [&](const FrameState& state, int passes) {
                        clock.advance_to(state.spp);
                        if (passes == 3) g_armed = true;
                      }};
  settings.passes = &control;
  const auto accel = make_accelerator("grid", scene.triangles);
  const RenderResult r = render(scene, *accel, settings, film);
  EXPECT_TRUE(r.interrupted);
  EXPECT_EQ(r.passes, 3);
  EXPECT_EQ(r.stop_reason, "interrupted");
  EXPECT_GT(r.abandoned_rays, 0u) << "the fourth pass had begun";
  settings.passes = nullptr;
  settings.test_nonfinite = nullptr;
  settings.spp = r.spp;
  const Film one_pass = test::render_scene(scene, settings, "grid");
  EXPECT_TRUE(test::bitwise_equal(film.rgb, one_pass.rgb)) << r.spp << " spp";
  EXPECT_TRUE(test::bitwise_equal(film.variance, one_pass.variance));
}

TEST(Passes, TheTimeBudgetEndsWithinItsTenPerCentAndPassesTakeAtMostFivePerCent) {
  const Scene scene = cornell(16);
  for (const double per_sample : {0.01, 0.0031, 0.047}) {
    Budget budget;
    budget.time_s = 1.0;
    FakeClock clock;
    clock.per_sample = per_sample;
    const Rendered r = render_budgeted(scene, budget, RenderSettings{}, clock);
    EXPECT_LE(clock.now, budget.time_s * (1 + 1e-12)) << per_sample;
    EXPECT_GE(clock.now, 0.9 * budget.time_s) << per_sample;
    for (std::size_t i = 1; i < r.pass_spp.size(); ++i)
      EXPECT_LE((r.pass_spp[i] - r.pass_spp[i - 1]) * per_sample, 0.05 * budget.time_s * (1 + 1e-12)) << per_sample;
  }
  // A sample per pixel that takes 20 % of the budget: passes of one sample,
  // as many as fit (it once stopped after the first).
  Budget budget;
  budget.time_s = 1.0;
  FakeClock slow;
  slow.per_sample = 0.2;
  const Rendered r = render_budgeted(scene, budget, RenderSettings{}, slow);
  EXPECT_EQ(r.result.spp, 5);
  EXPECT_LE(slow.now, budget.time_s * (1 + 1e-12));
  // --spp caps the passes under a budget.
  Budget capped;
  capped.time_s = 1.0;
  capped.spp_cap = 17;
  FakeClock clock;
  const Rendered c = render_budgeted(scene, capped, RenderSettings{}, clock);
  EXPECT_EQ(c.result.spp, 17);
  EXPECT_EQ(c.result.stop_reason, "spp");
}

TEST(PassPlanner, ATargetIsCheckedFromEightSamplesAndStopsBelowIt) {
  Budget budget;
  budget.target_relmse = 0.25;  // figures exact in binary, so the test sees no rounding
  PassPlanner planner(budget, [] { return 0.0; });
  EXPECT_EQ(planner.next_pass({0, 100, 0.0}), 8) << "the first pass reaches the first check";
  // Below the target from 8 spp on: stop.
  EXPECT_EQ(planner.next_pass({8, 100, 0.2}), 0);
  EXPECT_EQ(planner.stop_reason(), "target-relmse");
  // Above it: the samples the 1/n fall asks for, at most doubling.
  PassPlanner again(budget, [] { return 0.0; });
  again.next_pass({0, 100, 0.0});
  EXPECT_EQ(again.next_pass({8, 100, 0.3125}), 2);  // 8 x 0.3125 / 0.25 = 10
  EXPECT_EQ(again.next_pass({10, 100, 2.0}), 10);   // 80 asked for: doubling at most
  EXPECT_EQ(again.next_pass({20, 0, 0.5}), 0);       // every pixel retired
  EXPECT_EQ(again.stop_reason(), "converged");
  // Before 8 spp a low estimate does not stop a render (a time budget's first passes).
  Budget both = budget;
  both.time_s = 100;
  double t = 0;
  PassPlanner timed(both, [&t] { return t; });
  EXPECT_EQ(timed.next_pass({0, 10, 0.0}), 1);
  t = 0.01;
  EXPECT_EQ(timed.next_pass({1, 10, 0.0}), 7);
}

// kappa converge measures the film at each of its sample counts: passes end
// exactly there, and the cap ends the render.
TEST(PassPlanner, PassesEndAtEveryCheckpoint) {
  Budget budget;
  budget.spp_cap = 64;
  budget.checkpoints = {1, 2, 4, 16, 64};
  PassPlanner planner(budget, [] { return 0.0; });
  std::vector<int> totals;
  FrameState state{0, 100, 0.0};
  while (const int count = planner.next_pass(state)) totals.push_back(state.spp += count);
  EXPECT_EQ(totals, (std::vector<int>{1, 2, 4, 16, 64}));
  EXPECT_EQ(planner.stop_reason(), "spp");
}

// --checkpoint-every without a noise target: passes of about the longest
// pass, learnt from the last, ending at the cap (a render of --spp).
TEST(PassPlanner, ALongestPassSizesThePassesOfAnSppRender) {
  Budget budget;
  budget.spp_cap = 20;
  budget.longest_pass_s = 1;
  double t = 0;
  PassPlanner planner(budget, [&t] { return t; });
  FrameState state{0, 10, 0.0};
  std::vector<int> counts;
  while (const int count = planner.next_pass(state)) {
    counts.push_back(count);
    state.spp += count;
    t += 0.25 * count;  // a sample per pixel: 0.25 s
  }
  EXPECT_EQ(counts, (std::vector<int>{1, 4, 4, 4, 4, 3}));
  EXPECT_EQ(planner.stop_reason(), "spp");
}

// --resume: a noise target's passes after the checkpoint are those of the
// run not stopped (the estimate alone sizes them, --checkpoint-every or
// not); a time budget's first pass learns the speed again, and its budget
// counts the time spent before.
TEST(PassPlanner, AResumedPlannerTakesThePassesOfARunNotStopped) {
  Budget budget;
  budget.target_relmse = 0.01;
  budget.longest_pass_s = 0.5;  // no part in the sizing: a noise target sizes the passes
  double t = 0;
  const auto estimate = [](int spp) { return spp > 0 ? 0.64 / spp : 0.0; };  // falls as 1/n
  std::vector<FrameState> states;
  std::vector<int> counts;
  PassPlanner whole(budget, [&t] { return t; });
  FrameState state{0, 100, 0.0};
  while (const int count = whole.next_pass(state)) {
    counts.push_back(count);
    state.spp += count;
    state.relmse_estimate = estimate(state.spp);
    states.push_back(state);
    t += 1;  // slow passes: time would have cut them
  }
  ASSERT_GE(counts.size(), 4u);
  for (std::size_t k = 1; k + 1 < counts.size(); ++k) {
    PassPlanner resumed(budget, [&t] { return t; });
    resumed.resume(double(k));
    FrameState s = states[k - 1];
    std::vector<int> rest;
    while (const int count = resumed.next_pass(s)) {
      rest.push_back(count);
      s.spp += count;
      s.relmse_estimate = estimate(s.spp);
    }
    EXPECT_EQ(rest, std::vector<int>(counts.begin() + std::ptrdiff_t(k), counts.end())) << "resumed after pass " << k;
    EXPECT_EQ(resumed.stop_reason(), whole.stop_reason());
  }
  Budget timed;
  timed.time_s = 10;
  t = 100;
  PassPlanner again(timed, [&t] { return t; });
  again.resume(9.5);
  EXPECT_DOUBLE_EQ(again.elapsed(), 9.5);
  EXPECT_EQ(again.next_pass({50, 10, 0.0}), 1) << "the speed is learnt again";
  t += 0.1;  // 1 spp of 10 pixels: 0.1 s, and 0.4 s left
  EXPECT_EQ(again.next_pass({51, 10, 0.0}), 4);
  t += 0.4;
  EXPECT_EQ(again.next_pass({55, 10, 0.0}), 0);
  EXPECT_EQ(again.stop_reason(), "time-budget");
}

TEST(Passes, NonFiniteSamplesAreDroppedFromTheirPixelNotAveragedIn) {
  const Scene scene = cornell(16);
  RenderSettings settings;
  settings.spp = 4;
  const Film four = test::render_scene(scene, settings, "grid");
  // Samples 4..7 of every pixel read NaN: the 8-spp image is the 4-spp one.
  settings.spp = 8;
  settings.test_nonfinite = [](std::uint64_t, std::uint64_t sample) { return sample >= 4; };
  const auto accel = make_accelerator("grid", scene.triangles);
  Film film(scene.width, scene.height, settings.aov);
  const RenderResult r = render(scene, *accel, settings, film);
  EXPECT_EQ(r.nonfinite_samples, 4u * film.pixels());
  EXPECT_TRUE(test::bitwise_equal(film.rgb, four.rgb));
  for (float v : film.rgb) ASSERT_TRUE(std::isfinite(v));
  // A pixel whose every sample is non-finite reads 0, not NaN.
  settings.test_nonfinite = [](std::uint64_t pixel, std::uint64_t) { return pixel == 5; };
  const RenderResult all = render(scene, *accel, settings, film);
  EXPECT_EQ(all.nonfinite_samples, 8u);
  EXPECT_EQ(film.rgb[15], 0.0f);
  EXPECT_EQ(film.rgb[16], 0.0f);
  EXPECT_EQ(film.rgb[17], 0.0f);
}

TEST(Passes, AdaptiveSamplingIsTheSameImageForAnyThreadCount) {
  const Scene scene = cornell(32);
  RenderSettings settings;
  settings.aov.spp = settings.aov.variance = true;
  Budget budget;
  budget.target_relmse = 0.004;
  budget.adaptive = true;
  budget.adaptive_min_spp = 16;  // past the first pass (8): retiring waits for it
  budget.spp_cap = 256;
  const auto on = [&](int threads) {
    const ThreadLimit limit(threads);
    FakeClock clock;
    return render_budgeted(scene, budget, settings, clock);
  };
  const Rendered one = on(1), two = on(2);
  EXPECT_TRUE(test::bitwise_equal(one.film.rgb, two.film.rgb));
  EXPECT_TRUE(test::bitwise_equal(one.film.spp, two.film.spp));
  EXPECT_EQ(one.pass_spp, two.pass_spp);
  // Pixels stopped at different counts, none before the minimum, and those
  // that stopped early are below the target on their own.
  const SppSpread s = one.result.spp_spread;
  EXPECT_GE(s.min, 16u);
  EXPECT_LT(s.min, s.max);
  EXPECT_GT(s.mean, double(s.min));
  EXPECT_LT(s.mean, double(s.max));
  std::size_t early = 0;
  for (std::size_t i = 0; i < one.film.pixels(); ++i) {
    if (one.film.spp[i] >= float(s.max)) continue;
    ++early;
    double e = 0;
    for (int c = 0; c < 3; ++c) {
      const double x = one.film.rgb[3 * i + std::size_t(c)];
      e += one.film.variance[3 * i + std::size_t(c)] / (x * x + kRelmseEpsilon);
    }
    EXPECT_LT(e / 3, budget.target_relmse * 1.001) << "pixel " << i;
  }
  EXPECT_GT(early, 0u);
}

TEST(PixelSamples, WelfordMatchesTheTwoPassVarianceOfTheMean) {
  PixelSamples p;
  const float xs[] = {0.5f, 2.0f, 1.25f, 0.0f, 7.5f, 3.0f};
  for (float x : xs) p.add({x, 2 * x, 1.0f});
  const double n = 6;
  double mean = 0;
  for (float x : xs) mean += x;
  mean /= n;
  double ss = 0;
  for (float x : xs) ss += (x - mean) * (x - mean);
  EXPECT_NEAR(p.value(0), mean, 1e-15);
  EXPECT_NEAR(p.variance_of_mean(0), ss / (n - 1) / n, 1e-14);
  EXPECT_NEAR(p.variance_of_mean(1), 4 * ss / (n - 1) / n, 1e-13);
  EXPECT_EQ(p.variance_of_mean(2), 0.0);  // a constant channel
  const double expected = (ss / (n - 1) / n / (mean * mean + 0.01) + 4 * ss / (n - 1) / n / (4 * mean * mean + 0.01)) / 3;
  EXPECT_NEAR(p.relmse_estimate(), expected, 1e-14);
  EXPECT_EQ(p.finite, 6u);
  PixelSamples one;
  one.add({1, 1, 1});
  EXPECT_EQ(one.variance_of_mean(0), 0.0) << "one sample: unknown, not infinite";
}

}  // namespace
}  // namespace kappa
