// The replayable ray sets of bench, cast and calibrate.
#include "renderer/render/ray_sets.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "accel/factory.h"
#include "renderer/scene/scene_loader.h"
#include "test_util.h"

namespace kappa {
namespace {

Scene cornell() {
  Warnings w;
  return load_scene(test::assets_dir() / "cornell-box" / "scene.json", w);
}

TEST(RaySets, FewerCameraRaysThanPixelsStillCoverTheFilm) {
  const Scene scene = cornell();  // 512 x 512: the box's walls fill the film
  const auto accel = make_accelerator("naive", scene.triangles);
  for (std::size_t n : {std::size_t(64), std::size_t(256), std::size_t(1000), std::size_t(4096)}) {
    SCOPED_TRACE(n);
    const RaySet set = make_ray_set(RayClass::camera, scene, *accel, n, 0);
    ASSERT_EQ(set.rays.size(), n);
    float lo_x = 1, hi_x = -1, lo_y = 1, hi_y = -1;
    std::size_t hits = 0;
    for (const Ray& r : set.rays) {
      lo_x = std::min(lo_x, r.d.x), hi_x = std::max(hi_x, r.d.x);
      lo_y = std::min(lo_y, r.d.y), hi_y = std::max(hi_y, r.d.y);
      hits += accel->closest_hit(r).has_value();
    }
    // The camera looks along +z with a 39.3 degree field of view: directions
    // across the film span about 2 tan(19.65) = 0.71 in x and in y.
    EXPECT_GT(hi_x - lo_x, 0.5f);  // one column of pixels (the old spread) spans 0
    EXPECT_GT(hi_y - lo_y, 0.5f);
    EXPECT_GT(hits, n * 9 / 10);
  }
}

TEST(RaySets, ShadowAndBounceRaysStartFromCameraHits) {
  const Scene scene = cornell();
  const auto accel = make_accelerator("naive", scene.triangles);
  for (RayClass c : {RayClass::bounce, RayClass::shadow}) {
    const RaySet set = make_ray_set(c, scene, *accel, 256, 0);
    EXPECT_EQ(set.occlusion, c == RayClass::shadow);
    EXPECT_GT(set.rays.size(), 200u) << ray_class_name(c);
  }
}

}  // namespace
}  // namespace kappa
