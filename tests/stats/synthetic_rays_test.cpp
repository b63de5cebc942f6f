// The slab clip and the uniform lines every command draws its lines from.
#include "stats/synthetic_rays.h"

#include <gtest/gtest.h>

namespace kappa {
namespace {

const Vec3d kLo{0, 0, 0}, kHi{2, 1, 4};

TEST(ClipToBox, GivesTheChordOfARayThroughTheBox) {
  const auto chord = clip_to_box({-1, 0.5, 1}, {1, 0, 0}, kLo, kHi);
  ASSERT_TRUE(chord);
  EXPECT_EQ(chord->first, 1.0);
  EXPECT_EQ(chord->second, 3.0);
  // Narrowed by the given interval.
  const auto part = clip_to_box({-1, 0.5, 1}, {1, 0, 0}, kLo, kHi, 2.0, 2.5);
  ASSERT_TRUE(part);
  EXPECT_EQ(part->first, 2.0);
  EXPECT_EQ(part->second, 2.5);
}

TEST(ClipToBox, AxisParallelRaysAreTestedWithoutDividing) {
  // d.y = d.z = 0: inside the y and z slabs, or outside them.
  EXPECT_TRUE(clip_to_box({5, 0.5, 2}, {-1, 0, 0}, kLo, kHi));
  EXPECT_FALSE(clip_to_box({5, 1.5, 2}, {-1, 0, 0}, kLo, kHi));
  // On the box's face counts as inside (closed box).
  EXPECT_TRUE(clip_to_box({5, 1.0, 4.0}, {-1, 0, 0}, kLo, kHi));
}

TEST(ClipToBox, MissesAndRaysPointingAway) {
  EXPECT_FALSE(clip_to_box({-1, 3, 1}, {1, 0.1, 0}, kLo, kHi));
  EXPECT_FALSE(clip_to_box({-1, 0.5, 1}, {1, 0, 0}, kLo, kHi, -INFINITY, 0.5));  // ends before the box
}

TEST(UniformLines, EveryLineMeetsTheBoxAndStartsOutsideIt) {
  const auto lines = uniform_lines(kLo, kHi, 2000, 3);
  ASSERT_EQ(lines.size(), 2000u);
  for (const Ray& r : lines) {
    const auto chord = clip_to_box(Vec3d(r.o), Vec3d(r.d), kLo, kHi, 0.0, INFINITY);
    ASSERT_TRUE(chord);
    EXPECT_GT(chord->first, 0.0);
  }
}

}  // namespace
}  // namespace kappa
