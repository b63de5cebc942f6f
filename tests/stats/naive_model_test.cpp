// The naive accelerator's model: its features, its fit, and what
// --accel auto reads from it.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "stats/naive_model.h"

namespace kappa {
namespace {

TimedNaiveLoad timed(RenderClass k, double triangles, double hit_fraction, const std::vector<double>& ns) {
  TimedNaiveLoad m;
  m.load = NaiveLoad{k, 1000, 1000 * hit_fraction, triangles};
  NaiveModel exact;
  exact.ns = ns;
  m.seconds = exact.seconds(m.load);
  m.label = std::string(kRenderClassNames[k]) + " " + std::to_string(int(triangles));
  return m;
}

TEST(NaiveModel, AClosestHitQueryTestsEveryTriangleAndAnOccludedShadowRayCostsTheOccludedRate) {
  NaiveModel m;
  m.ns = {100, 5, 1};
  // Closest-hit: T0 + N Th whatever it hit.
  EXPECT_DOUBLE_EQ(m.seconds({kBounce2, 10, 7, 1000}), 10 * (100 + 1000 * 5) * 1e-9);
  // Shadow: the unoccluded rays test all N, the occluded ones at Th_occluded.
  EXPECT_DOUBLE_EQ(m.seconds({kShadow, 10, 4, 1000}), (10 * 100 + 6 * 1000 * 5 + 4 * 1000 * 1) * 1e-9);
  EXPECT_DOUBLE_EQ(m.seconds({kShadow, 0, 0, 1000}), 0.0);  // no rays: no division by zero
}

TEST(NaiveModel, TheFitRecoversTheConstantsThatMadeTheTimes) {
  const std::vector<double> ns = {120, 5.5, 0.9};
  std::vector<TimedNaiveLoad> loads;
  for (double n : {32.0, 112.0, 1012.0, 3676.0}) {
    loads.push_back(timed(kCamera, n, 1.0, ns));
    loads.push_back(timed(kShadow, n, 0.8, ns));
    loads.push_back(timed(kShadow, n, 0.2, ns));
  }
  NaiveModel m;
  fit(m, loads);
  for (std::size_t i = 0; i < ns.size(); ++i) EXPECT_NEAR(m.ns[i], ns[i], 1e-6 * ns[i]) << m.terms[i];
  EXPECT_LT(m.rms_relative_error, 1e-9);
}

TEST(NaiveModel, MeasurementsOfOneSizeCannotTellT0FromTh) {
  const std::vector<double> ns = {120, 5.5, 0.9};
  const std::vector<TimedNaiveLoad> one_size = {timed(kCamera, 32, 1, ns), timed(kBounce1, 32, 0.5, ns),
                                                timed(kShadow, 32, 0.5, ns), timed(kShadow, 32, 0.1, ns)};
  NaiveModel m;
  EXPECT_THROW(fit(m, one_size), std::runtime_error);
  EXPECT_THROW(fit(m, std::vector<TimedNaiveLoad>(one_size.begin(), one_size.begin() + 2)), std::runtime_error);
}

TEST(NaiveModel, JsonRoundTripAndRefusals) {
  NaiveModel m;
  m.ns = {120, 5.5, 0.9};
  m.rms_relative_error = 0.25;
  NaiveModel back;
  ASSERT_TRUE(from_json(nlohmann::json::parse(to_json(m).dump()), back));
  EXPECT_EQ(back.ns, m.ns);
  EXPECT_EQ(back.rms_relative_error, 0.25);
  nlohmann::json missing = to_json(m);
  missing["constants"].erase("Th_occluded_ns");
  EXPECT_FALSE(from_json(missing, back));
  nlohmann::json negative = to_json(m);
  negative["constants"]["T0_ns"] = -1;
  EXPECT_FALSE(from_json(negative, back));
}

}  // namespace
}  // namespace kappa
