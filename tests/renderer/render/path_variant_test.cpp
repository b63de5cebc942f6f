// The integrator a frame runs (path_variant.h): chosen from what the scene
// has, and the same image bit for bit as the general integrator, which keeps
// every branch behind run-time checks.
#include <gtest/gtest.h>

#include <cstring>

#include "renderer/render/path_variant.h"
#include "renderer/render/render_helpers.h"
#include "renderer/scene/scene_loader.h"
#include "test_util.h"

namespace kappa {
namespace {

TEST(PathVariant, TheSceneDecidesWhichLightsAreSampled) {
  const auto name = [](SceneLighting l, LightSampling s, bool aovs = false, bool specialise = true) {
    return path_variant_name(choose_path_variant(l, s, aovs, specialise));
  };
  EXPECT_EQ(name({true, false, false}, LightSampling::mis), "mis: triangles");  // the Cornell box
  EXPECT_EQ(name({false, true, true}, LightSampling::mis), "mis: environment");
  EXPECT_EQ(name({true, true, true}, LightSampling::nee), "nee: triangles + environment");
  EXPECT_EQ(name({true, true, true}, LightSampling::bsdf), "bsdf + environment");
  EXPECT_EQ(name({true, false, false}, LightSampling::bsdf), "bsdf");
  // No light at all: nothing to sample, whatever was asked.
  EXPECT_EQ(name({false, false, false}, LightSampling::mis), "bsdf");
  EXPECT_EQ(name({false, false, false}, LightSampling::nee, true), "bsdf, first hit");
  // An environment too dim for its power to register (its luminance rounds to
  // 0 in float) is looked up but cannot be sampled.
  EXPECT_EQ(name({false, true, false}, LightSampling::mis), "bsdf + environment");
  EXPECT_EQ(name({true, true, false}, LightSampling::mis), "mis: triangles + environment");
  // The general variant of each strategy: everything on.
  EXPECT_EQ(name({true, false, false}, LightSampling::mis, false, false), "mis: triangles + environment, first hit");
  EXPECT_EQ(name({false, false, false}, LightSampling::bsdf, false, false), "bsdf + environment, first hit");
  // Every variant chosen is one the frames are compiled for.
  for (bool t : {false, true})
    for (bool e : {false, true})
      for (LightSampling s : {LightSampling::mis, LightSampling::nee, LightSampling::bsdf})
        for (bool aovs : {false, true})
          for (bool specialise : {false, true}) {
            const PathVariant v = choose_path_variant({t, e, e}, s, aovs, specialise);
            int compiled = 0;
            with_path_variant(v, [&]<PathVariant V>() { ++compiled; });
            EXPECT_EQ(compiled, 1) << path_variant_name(v);
          }
}

/// A floor and a wall under a small light and a sky, as asked.
Scene lit_room(bool light, bool sky) {
  Scene s;
  s.materials.push_back(Material{"white", {0.7f, 0.7f, 0.7f}, {0, 0, 0}});
  s.materials.push_back(Material{"light", {0, 0, 0}, {20, 18, 15}});
  s.materials.push_back(Material{"grey", {0.5f, 0.5f, 0.5f}, {0, 0, 0}});
  test::add_box(s, {-2, -1, -2}, {2, 0, 2}, false, 0);   // the floor, a slab
  test::add_box(s, {-2, 0, 1.5f}, {2, 2, 2}, false, 0);  // a wall
  if (light) test::add_box(s, {-0.3f, 1.5f, -0.3f}, {0.3f, 1.6f, 0.3f}, false, 1);
  test::add_box(s, {-0.5f, 0, -0.5f}, {0.5f, 0.8f, 0.5f}, false, 2);
  if (sky) s.environment = {0.4f, 0.5f, 0.6f};
  s.camera = CameraSpec{{0, 1.2f, -4}, {0, 0.4f, 0}, {0, 1, 0}, 50.0f};
  s.width = s.height = 24;
  return s;
}

// Specialising removes only work whose result is known: every variant renders
// the general integrator's image bit for bit (RGB and AOVs), under every
// strategy and sampler. An independent sampler's numbers are drawn in order,
// so a variant that skipped one (the light choice with a single kind of
// light) would shift every later number and fail here.
TEST(PathVariant, EverySpecialisedVariantRendersTheGeneralImage) {
  Warnings warnings;
  Scene cornell = load_scene(test::assets_dir() / "cornell-box" / "scene.json", warnings);
  cornell.width = cornell.height = 24;
  const std::vector<std::pair<const char*, Scene>> scenes = {
      {"cornell", cornell},
      {"light", lit_room(true, false)},
      {"sky", lit_room(false, true)},
      {"light and sky", lit_room(true, true)},
      {"dark", lit_room(false, false)}};
  int variants_seen = 0;
  for (const auto& [label, scene] : scenes)
    for (LightSampling strategy : {LightSampling::mis, LightSampling::nee, LightSampling::bsdf})
      for (SamplerKind sampler : {SamplerKind::independent, SamplerKind::stratified, SamplerKind::sobol})
        for (bool aovs : {false, true}) {
          RenderSettings settings;
          settings.spp = 4;
          settings.light_sampling = strategy;
          settings.sampler = sampler;
          settings.aov.albedo = settings.aov.depth = aovs;
          SCOPED_TRACE(std::string(label) + ", " + light_sampling_name(strategy) + ", " + sampler_name(sampler) +
                       (aovs ? ", AOVs" : ""));
          const Film specialised = test::render_scene(scene, settings);
          settings.specialise = false;
          const Film general = test::render_scene(scene, settings);
          EXPECT_TRUE(test::bitwise_equal(specialised.rgb, general.rgb));
          EXPECT_TRUE(test::bitwise_equal(specialised.albedo, general.albedo));
          EXPECT_TRUE(test::bitwise_equal(specialised.depth, general.depth));
          ++variants_seen;
        }
  EXPECT_EQ(variants_seen, 5 * 3 * 3 * 2);
}

// The report names the variant that ran.
TEST(PathVariant, TheResultNamesTheVariantThatRan) {
  RenderSettings settings;
  settings.spp = 1;
  const Scene sky = lit_room(false, true);
  const auto accel = make_accelerator("naive", sky.triangles);
  Film film(sky.width, sky.height, settings.aov);
  EXPECT_EQ(render(sky, *accel, settings, film).path_variant, "mis: environment");
  settings.light_sampling = LightSampling::nee;
  settings.aov.depth = true;
  Film with_depth(sky.width, sky.height, settings.aov);
  EXPECT_EQ(render(sky, *accel, settings, with_depth).path_variant, "nee: environment, first hit");
}

}  // namespace
}  // namespace kappa
