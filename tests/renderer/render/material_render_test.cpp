// Renders through the materials (renderer/bsdf/) whose value is known in
// closed form, the material scenes bitwise alike under every exact
// accelerator and thread count, and shading normals that add no energy.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "core/thread_limit.h"
#include "renderer/bsdf/local_frame.h"
#include "renderer/render/render_helpers.h"
#include "renderer/scene/obj/obj_loader.h"
#include "renderer/scene/scene_loader.h"
#include "test_util.h"

namespace kappa {
namespace {

Material glass(float roughness = 0.0f) {
  Material m;
  m.name = "glass";
  m.transmission = 1;
  m.roughness = roughness;
  m.specular = 0.5f;
  m.ior = 1.5f;
  return m;
}

/// A closed dielectric in a uniform environment, with no light sampling
/// possible through its delta lobes: every path that leaves carries exactly
/// the environment (each reflection weighs R / R, each refraction T / T
/// times 1/eta'^2, undone on the way out).
TEST(MaterialRender, SmoothGlassInAUniformEnvironmentRendersTheEnvironment) {
  Scene s;
  s.materials.push_back(glass());
  test::add_sphere(s, {0, 0, 0}, 1.0f, 24, 48, false, 0);
  s.environment = {0.3f, 0.5f, 0.7f};
  s.camera = CameraSpec{{0, 0, -3.2f}, {0, 0, 0}, {0, 1, 0}, 45.0f};
  s.width = s.height = 32;
  RenderSettings settings;
  settings.spp = test::scaled(16, 4);
  settings.max_depth = 256;
  settings.rr_depth = -1;
  const Film film = test::render_scene(s, settings, "grid");
  std::size_t off = 0;
  for (std::size_t i = 0; i < film.pixels(); ++i)
    for (int c = 0; c < 3; ++c) {
      const float expected = c == 0 ? 0.3f : c == 1 ? 0.5f : 0.7f;
      off += std::abs(film.rgb[3 * i + std::size_t(c)] - expected) > 1e-4f * expected;
    }
  // Paths still inside after 256 vertices (trapped by total internal
  // reflection between the facets) are the only loss.
  EXPECT_LE(off, film.pixels() * 3 / 100) << off << " of " << 3 * film.pixels() << " channels";
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(test::channel_stats(film, c).mean, s.environment[c], 1e-3 * s.environment[c]) << c;
}

/// A smooth metal of base colour F0 seen at 60 degrees reflects Schlick's
/// F(0.5) of a uniform emitter: the environment, or a large emissive quad
/// (light sampling cannot reach a mirror's reflection: it counts in full).
TEST(MaterialRender, AMirrorFacingAUniformEmitterReturnsFresnelTimesLe) {
  const Vec3f f0{0.2f, 0.5f, 0.8f};
  const Vec3f Le{2.0f, 1.0f, 0.5f};
  for (bool quad : {false, true})
  for (bool from_behind : {false, true}) {
    Scene s;
    Material mirror;
    mirror.name = "mirror";
    mirror.albedo = f0;
    mirror.metallic = 1;
    mirror.roughness = 0;
    // A metal reflects on both sides, whatever else it would be (its glass
    // part has no weight): seen from behind its winding, it is the same mirror.
    if (from_behind) mirror.transmission = 1;
    s.materials.push_back(mirror);
    if (from_behind) {
      s.triangles.push_back({{-50, 0, -50}, {50, 0, -50}, {50, 0, 50}});  // facing down, -y
      s.triangles.push_back({{-50, 0, -50}, {50, 0, 50}, {-50, 0, 50}});
      s.material_of.insert(s.material_of.end(), {0, 0});
    } else {
      test::add_box(s, {-50, -1, -50}, {50, 0, 50}, false, 0);
    }
    if (quad) {
      s.materials.push_back(Material{"lamp", {0, 0, 0}, Le});
      // Square to the mirrored rays (0, 0.5, 0.866), 1000 away, facing back at them.
      const Vec3f c{0, 500, 866.0254f}, x{300, 0, 0}, u{0, 259.80762f, -150};
      const Vec3f a = c - x - u, b = c + x - u, cc = c + x + u, d = c - x + u;
      s.triangles.push_back({a, cc, b});
      s.triangles.push_back({a, d, cc});
      s.material_of.push_back(1);
      s.material_of.push_back(1);
    } else {
      s.environment = Le;
    }
    // The camera looks down at 30 degrees from the horizon: 60 from the normal.
    const float d = 10.0f;
    s.camera = CameraSpec{{0, d * 0.5f, -d * 0.8660254f}, {0, 0, 0}, {0, 1, 0}, 0.05f};
    s.width = s.height = 4;
    RenderSettings settings;
    settings.spp = 4;
    const Film film = test::render_scene(s, settings, "grid");
    const Vec3f F = bsdf::fresnel_schlick(f0, 0.5f);
    for (std::size_t i = 0; i < film.pixels(); ++i)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(film.rgb[3 * i + std::size_t(c)], F[c] * Le[c], 2e-3 * F[c] * Le[c])
            << (quad ? "quad" : "environment") << (from_behind ? " from behind" : "") << " pixel " << i << " channel " << c;
  }
}

/// The closed furnace of albedo rho emitting Le everywhere, seen from inside;
/// with `general`, an unused glossy material makes the frame run the general
/// BSDF (every material through renderer/bsdf/).
Scene furnace_box(float rho, float Le, bool general) {
  Scene s;
  s.materials.push_back(Material{"furnace", {rho, rho, rho}, {Le, Le, Le}});
  if (general) {
    Material glossy;
    glossy.specular = 0.5f;
    s.materials.push_back(glossy);
  }
  test::add_box(s, {-1, -1, -1}, {1, 1, 1}, /*inward=*/true, 0);
  s.camera = CameraSpec{{0.1f, -0.05f, 0.02f}, {0.3f, 0.2f, 1.0f}, {0, 1, 0}, 90.0f};
  s.width = s.height = 48;
  return s;
}

Film render_furnace(const Scene& s) {
  RenderSettings settings;
  settings.spp = test::scaled(64, 8);
  settings.max_depth = 64;
  return test::render_scene(s, settings, "grid");
}

/// The closed furnace of rho 0.5 emitting Le everywhere reads Le / (1 - rho).
/// Shading normals tilted at random (up to about 20 degrees from each face's)
/// may lose energy (directions below the surface are black) but never add
/// any, in the Lambertian frame and through the general BSDF alike.
TEST(MaterialRender, ShadingNormalsAddNoEnergy) {
  const float rho = 0.5f, Le = 0.5f;
  const double expected = Le / (1.0 - rho);
  for (bool general : {false, true}) {
    Scene s = furnace_box(rho, Le, general);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-0.25f, 0.25f);
    for (const Triangle& t : s.triangles) {
      const Vec3f n = normalize(cross(t.v1 - t.v0, t.v2 - t.v0));
      TriangleNormals tn;
      for (Vec3f& v : tn.n) v = normalize(n + Vec3f{u(rng), u(rng), u(rng)});
      s.normals.push_back(tn);
    }
    const Film film = render_furnace(s);
    for (int c = 0; c < 3; ++c) {
      const auto st = test::channel_stats(film, c);
      std::printf("%s furnace with tilted shading normals, channel %d: %.5f (no tilt: %.5f)\n",
                  general ? "general" : "Lambertian", c, st.mean, expected);
      EXPECT_LT(st.mean, expected + 4 * st.standard_error) << (general ? "general" : "Lambertian");
      EXPECT_GT(st.mean, 0.8 * expected) << (general ? "general" : "Lambertian");
    }
  }
}

/// The general BSDF with Lambertian parameters is the Lambertian frame's
/// estimator: the closed furnace reads Le / (1 - rho).
TEST(MaterialRender, TheGeneralBsdfWithLambertianParametersConvergesInTheFurnace) {
  const float rho = 0.5f, Le = 0.5f;
  const Film film = render_furnace(furnace_box(rho, Le, true));
  for (int c = 0; c < 3; ++c) {
    const auto st = test::channel_stats(film, c);
    EXPECT_NEAR(st.mean, Le / (1 - rho), 4 * st.standard_error + 1e-6) << c;
  }
}

Scene material_scene(const std::string& folder, int width, int height) {
  Warnings warnings;
  Scene scene = load_scene(test::assets_dir() / folder / "scene.json", warnings);
  scene.width = width;
  scene.height = height;
  return scene;
}

TEST(MaterialRender, MaterialScenesAreBitwiseAlikeUnderEveryExactAcceleratorAndThreadCount) {
  for (const char* folder : {"material-box", "veach-mis", "textured-box"}) {
    const Scene scene = material_scene(folder, 32, 24);
    RenderSettings settings;
    settings.spp = 4;
    settings.aov = AovSelection{true, true, true};
    Film naive(1, 1, settings.aov);
    {
      const ThreadLimit limit(1);
      naive = test::render_scene(scene, settings, "naive");
    }
    for (const char* exact : {"grid", "grid2"})
      for (int threads : {1, 2, 4}) {
        const ThreadLimit limit(threads);
        const Film f = test::render_scene(scene, settings, exact);
        EXPECT_TRUE(test::bitwise_equal(naive.rgb, f.rgb)) << folder << " " << exact << " " << threads;
        EXPECT_TRUE(test::bitwise_equal(naive.albedo, f.albedo)) << folder << " " << exact << " " << threads;
      }
    double sum = 0;
    for (float v : naive.rgb) {
      ASSERT_TRUE(std::isfinite(v)) << folder;
      sum += v;
    }
    EXPECT_GT(sum, 0.0) << folder;
    // Embree rounds its intersections otherwise: paths part where a hit moves
    // by an ulp, so its image agrees in the mean, not bit for bit.
    const Film embree = test::render_scene(scene, settings, "embree");
    double embree_sum = 0;
    for (float v : embree.rgb) embree_sum += v;
    EXPECT_NEAR(embree_sum, sum, 0.01 * sum) << folder;
  }
}

/// Every MTL value Kappa clamps (with a warning) and the extremes it keeps
/// render without a single NaN or infinite sample: a quad each, under a
/// light and the sky, through every lobe.
TEST(MaterialRender, ClampedAndExtremeMtlValuesRenderNoNonFiniteSample) {
  const char* materials[] = {
      "Pr 3\nPm 1",         "Pm -1\nKs 1 1 1",       "Ns 5000\nKs 0.5 0.5 0.5", "Ns -5\nillum 2",
      "Kd 2 2 2\nKs 1 1 1", "Kd -1 0 0\nillum 2",    "Ni 0.5\nillum 7",         "Tf 2 2 2\nillum 7\nNi 1.5",
      "illum 0",             "illum 10",               "Ks 5 5 5\nillum 2",       "d 2",
      "Tr -1",               "Ni 1.0001\nillum 4",    "Ni 100\nillum 4\nNs 10", "Pr 0\nPm 1",
      "Pr 1e-9\nillum 4",   "Pr 1\nillum 4\nNi 3",  "Kd 0 0 0\nillum 3\nKa 1 1 1\nPr 0.5",
      "illum 6\nNs 900",
  };
  test::TempDir dir;
  std::string mtl = "newmtl light\nKd 0 0 0\nKe 20 20 20\n";
  std::string obj = "mtllib m.mtl\n";
  int n = 0;
  const int count = int(std::size(materials));
  for (int i = 0; i < count; ++i) {
    mtl += "newmtl m" + std::to_string(i) + "\n" + materials[i] + "\n";
    const float x = float(i % 5) * 1.1f - 2.7f, y = float(i / 5) * 1.1f - 2.2f;
    char quad[256];
    std::snprintf(quad, sizeof quad, "v %g %g 0\nv %g %g 0\nv %g %g 0.3\nv %g %g 0.3\n", x, y, x + 1, y, x + 1,
                  y + 1, x, y + 1);
    obj += std::string(quad) + "usemtl m" + std::to_string(i) + "\nf " + std::to_string(n + 1) + " " +
           std::to_string(n + 2) + " " + std::to_string(n + 3) + " " + std::to_string(n + 4) + "\n";
    n += 4;
  }
  obj += "v -1 -1 3\nv -1 1 3\nv 1 1 3\nv 1 -1 3\nusemtl light\nf " + std::to_string(n + 1) + " " +
         std::to_string(n + 2) + " " + std::to_string(n + 3) + " " + std::to_string(n + 4) + "\n";
  test::write_file(dir / "m.obj", obj);
  test::write_file(dir / "m.mtl", mtl);
  Scene s;
  Warnings w;
  load_obj(dir / "m.obj", s, w);
  ASSERT_EQ(s.materials.size(), std::size_t(count + 1));
  EXPECT_GE(w.size(), 10u);  // the clamped values say so
  s.environment = {0.2f, 0.3f, 0.4f};
  s.camera = CameraSpec{{0, 0, 8}, {0, 0, 0}, {0, 1, 0}, 50.0f};
  s.width = s.height = 48;
  for (LightSampling strategy : {LightSampling::mis, LightSampling::nee, LightSampling::bsdf}) {
    RenderSettings settings;
    settings.spp = test::scaled(16, 4);
    settings.light_sampling = strategy;
    const auto accel = make_accelerator("grid", s.triangles);
    Film film(s.width, s.height, {});
    const RenderResult r = render(s, *accel, settings, film);
    EXPECT_EQ(r.nonfinite_samples, 0u) << light_sampling_name(strategy);
    for (float v : film.rgb) ASSERT_TRUE(std::isfinite(v)) << light_sampling_name(strategy);
  }
}

}  // namespace
}  // namespace kappa
