// glTF's lights. Punctual lights (Scene::punctual_lights) in next-event
// estimation: a point light at distance d gives the irradiance I/d^2, a spot
// light's cone falls off as KHR_lights_punctual's reference does, a
// directional light casts the shadow of what blocks it, and each adds to the
// other lights without a MIS weight (BSDF sampling alone cannot find them).
// A double-sided emitter (Material::emits_both_sides) lights its back as its
// front.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <numbers>

#include "renderer/render/render_helpers.h"
#include "test_util.h"

namespace kappa {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr float kAlbedo = 0.5f;

/// A white Lambertian floor (y = 0, 2 km wide) and nothing else: no
/// environment, so the punctual lights alone light it.
Scene floor_scene() {
  Scene s;
  Material white;
  white.name = "white";
  white.albedo = {kAlbedo, kAlbedo, kAlbedo};
  s.materials.push_back(white);
  const float r = 1000;
  s.triangles.push_back(Triangle{{-r, 0, -r}, {-r, 0, r}, {r, 0, r}});
  s.triangles.push_back(Triangle{{-r, 0, -r}, {r, 0, r}, {r, 0, -r}});
  s.material_of = {0, 0};
  s.width = s.height = 4;
  return s;
}

/// A camera 1 above (x, 0, z) looking straight down with a narrow view: every
/// pixel sees the floor within 0.01 of that point.
CameraSpec looking_down_at(float x, float z, float height = 1.0f) {
  return CameraSpec{{x, height, z}, {x, 0, z + 0.001f}, {0, 0, 1}, 1.0f};
}

double mean_green(const Scene& s, LightSampling strategy, const std::string& accel = "grid") {
  RenderSettings settings;
  settings.spp = 4;
  settings.max_depth = 1;
  settings.light_sampling = strategy;
  const Film film = test::render_scene(s, settings, accel);
  return test::channel_stats(film, 1).mean;
}

PunctualLight point_light(Vec3f at, float intensity) {
  PunctualLight l;
  l.type = PunctualLight::Type::point;
  l.position = at;
  l.intensity = {intensity, intensity, intensity};
  return l;
}

TEST(PunctualLights, APointLightAtDistanceDGivesTheIrradianceIOverDSquared) {
  Scene s = floor_scene();
  const float I = 3.0f, d = 2.0f;
  s.punctual_lights.push_back(point_light({0, d, 0}, I));
  s.camera = looking_down_at(0, 0);
  // Radiance = albedo / pi * E, E = I / d^2 (the light straight above).
  const double expected = kAlbedo / kPi * I / (d * d);
  for (LightSampling strategy : {LightSampling::mis, LightSampling::nee}) {
    for (const char* accel : {"naive", "grid", "grid2", "embree"})
      EXPECT_NEAR(mean_green(s, strategy, accel), expected, 2e-4 * expected) << light_sampling_name(strategy) << " " << accel;
  }
  // BSDF sampling cannot hit a point: the documented black image.
  EXPECT_EQ(mean_green(s, LightSampling::bsdf), 0.0);
}

TEST(PunctualLights, ASpotLightFallsOffAcrossItsConeAsTheExtensionSpecifies) {
  const float I = 4.0f, h = 2.0f;
  const double inner = 0.25, outer = 0.5;
  for (double theta : {0.0, 0.3, 0.375, 0.45, 0.6}) {
    Scene s = floor_scene();
    PunctualLight spot = point_light({0, h, 0}, I);
    spot.type = PunctualLight::Type::spot;
    spot.direction = {0, -1, 0};
    spot.cos_inner = float(std::cos(inner));
    spot.cos_outer = float(std::cos(outer));
    s.punctual_lights.push_back(spot);
    const float x = float(h * std::tan(theta));
    s.camera = looking_down_at(x, 0);
    // E = I t^2 cos(theta) / r^2, r = h / cos(theta); t by the reference.
    const double t = std::clamp((std::cos(theta) - std::cos(outer)) / (std::cos(inner) - std::cos(outer)), 0.0, 1.0);
    const double c = std::cos(theta);
    const double expected = kAlbedo / kPi * I * t * t * c * c * c / (h * h);
    // The view spans +-0.01 on the floor: the cone's slope there is the tolerance.
    EXPECT_NEAR(mean_green(s, LightSampling::mis), expected, 0.02 * kAlbedo / kPi * I / (h * h) + 1e-6) << theta;
    if (theta > outer) {
      EXPECT_EQ(mean_green(s, LightSampling::mis), 0.0) << "outside the outer cone";
    }
  }
}

TEST(PunctualLights, ADirectionalLightCastsTheShadowOfWhatBlocksIt) {
  Scene s = floor_scene();
  // A square blocker at y = 1 over x, z in [-0.5, 0.5], facing up and down.
  s.triangles.push_back(Triangle{{-0.5f, 1, -0.5f}, {0.5f, 1, 0.5f}, {-0.5f, 1, 0.5f}});
  s.triangles.push_back(Triangle{{-0.5f, 1, -0.5f}, {0.5f, 1, -0.5f}, {0.5f, 1, 0.5f}});
  s.material_of = {0, 0, 0, 0};
  PunctualLight sun;
  sun.type = PunctualLight::Type::directional;
  sun.direction = {0, -1, 0};
  const float E = 2.0f;
  sun.intensity = {E, E, E};
  s.punctual_lights.push_back(sun);
  for (const char* accel : {"naive", "grid", "grid2", "embree"}) {
    s.camera = looking_down_at(0, 0, 0.5f);  // under the blocker
    EXPECT_EQ(mean_green(s, LightSampling::mis, accel), 0.0) << accel;
    s.camera = looking_down_at(2, 0);  // in the open
    EXPECT_NEAR(mean_green(s, LightSampling::mis, accel), kAlbedo / kPi * E, 1e-5) << accel;
  }
}

TEST(PunctualLights, AddToTriangleLightsWithoutAWeightAndKeepEveryAcceleratorsImageBitwise) {
  Scene s = floor_scene();
  // An emissive square high above, and a point light: their sum.
  Material light;
  light.name = "light";
  light.albedo = {0, 0, 0};
  light.emission = {1, 1, 1};
  s.materials.push_back(light);
  s.triangles.push_back(Triangle{{-1, 50, -1}, {1, 50, 1}, {1, 50, -1}});
  s.triangles.push_back(Triangle{{-1, 50, -1}, {-1, 50, 1}, {1, 50, 1}});
  s.material_of = {0, 0, 1, 1};
  s.camera = looking_down_at(0, 0);
  s.width = s.height = 8;
  RenderSettings settings;
  settings.spp = 64;
  settings.max_depth = 1;
  const Film without = test::render_scene(s, settings, "grid");
  s.punctual_lights.push_back(point_light({0, 2, 0}, 3.0f));
  const Film naive = test::render_scene(s, settings, "naive");
  for (const char* accel : {"grid", "grid2"})
    EXPECT_TRUE(test::bitwise_equal(naive.rgb, test::render_scene(s, settings, accel).rgb)) << accel;
  // The point light's share is its own irradiance (no weight against the
  // square's samples); the square's share is unbiased either way.
  const double added = test::channel_stats(naive, 1).mean - test::channel_stats(without, 1).mean;
  const double expected = kAlbedo / kPi * 3.0 / 4.0;
  EXPECT_NEAR(added, expected, 0.03 * expected);
}

TEST(EmittersBothSides, ADoubleSidedEmitterLightsFromItsBackWhatItsFrontWould) {
  // A 1 x 1 emitter 1 above the floor, facing down (its front to the floor)
  // or up (its back), one-sided or both ways, by every strategy.
  auto render_with = [](bool facing_down, bool both, LightSampling strategy) {
    Scene s = floor_scene();
    Material light;
    light.name = "light";
    light.albedo = {0, 0, 0};
    light.emission = {2, 2, 2};
    light.emits_both_sides = both;
    s.materials.push_back(light);
    Triangle a{{-0.5f, 1, -0.5f}, {0.5f, 1, -0.5f}, {0.5f, 1, 0.5f}};
    Triangle b{{-0.5f, 1, -0.5f}, {0.5f, 1, 0.5f}, {-0.5f, 1, 0.5f}};
    if (!facing_down) {  // counter-clockwise seen from above: the normal points up
      std::swap(a.v1, a.v2);
      std::swap(b.v1, b.v2);
    }
    s.triangles.push_back(a);
    s.triangles.push_back(b);
    s.material_of = {0, 0, 1, 1};
    s.camera = looking_down_at(0.3f, 0.2f, 0.5f);
    s.width = s.height = 8;
    RenderSettings settings;
    settings.spp = test::scaled(256, 64);
    settings.max_depth = 1;
    settings.light_sampling = strategy;
    return test::channel_stats(test::render_scene(s, settings, "grid"), 1);
  };
  for (LightSampling strategy : {LightSampling::mis, LightSampling::nee, LightSampling::bsdf}) {
    const test::ChannelStats front = render_with(true, false, strategy);
    const test::ChannelStats back_one_sided = render_with(false, false, strategy);
    const test::ChannelStats back_both = render_with(false, true, strategy);
    EXPECT_GT(front.mean, 0.05) << light_sampling_name(strategy);
    EXPECT_EQ(back_one_sided.mean, 0.0) << light_sampling_name(strategy);
    EXPECT_NEAR(back_both.mean, front.mean, 4.0 * (front.standard_error + back_both.standard_error) + 1e-4)
        << light_sampling_name(strategy);
  }
}

}  // namespace
}  // namespace kappa
