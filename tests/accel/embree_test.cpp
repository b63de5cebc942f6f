// Embree agrees with naive up to float rounding: the same triangle and t
// within kRelT, except on ties (two triangles at the same t, a ray through a
// shared edge) and grazes (a ray through a silhouette edge or vertex, hit by
// one test and missed by the other). Those are detected and counted; on
// random rays they must be rare (none seen), and any_hit must agree exactly.
// Images agree with grid's to well within Monte Carlo noise.
#include "accel/embree.h"
#include "accel/factory.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>
#include <xmmintrin.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <random>

#include "accel/naive.h"
#include "renderer/render/render_helpers.h"
#include "renderer/scene/obj/obj_loader.h"
#include "renderer/scene/scene_loader.h"
#include "test_util.h"

namespace kappa {
namespace {

/// Relative tolerance on t. Embree's robust test and naive's differ only in
/// rounding: typically 1e-6, at most 1.5e-5 measured on the random rays below
/// and 6e-5 on rays aimed at vertices (grazing hits are the worst).
constexpr double kRelT = 1e-4;
/// A hit this close (in barycentrics) to an edge may belong to either triangle.
constexpr float kEdge = 1e-4f;

struct Agreement {
  std::size_t rays = 0, hits = 0;
  std::size_t ties = 0;        ///< different triangles at the same t
  std::size_t grazes = 0;      ///< one side hit an edge or vertex the other slipped past
  std::size_t any_differs = 0;  ///< any_hit answers that differ (only allowed on grazes)
  std::size_t mismatches = 0;
  double max_rel_t = 0;  ///< same triangle: |t_embree - t_naive| / t_naive
  double max_bary = 0;   ///< same triangle: largest barycentric difference
};

std::string describe(const Ray& r, const std::optional<Hit>& a, const std::optional<Hit>& b) {
  auto hit = [](const std::optional<Hit>& h) {
    if (!h) return std::string("miss");
    char s[120];
    std::snprintf(s, sizeof s, "%u t=%.9g b=(%.3g,%.3g,%.3g)", h->triangle, h->t, h->b0, h->b1, h->b2);
    return std::string(s);
  };
  char ray[200];
  std::snprintf(ray, sizeof ray, "o=(%.9g,%.9g,%.9g) d=(%.9g,%.9g,%.9g) tmin=%.9g tmax=%.9g", r.o.x, r.o.y, r.o.z,
                r.d.x, r.d.y, r.d.z, r.tmin, r.tmax);
  return std::string(ray) + ": naive " + hit(a) + ", embree " + hit(b);
}

bool on_edge(const Hit& h) { return std::min({h.b0, h.b1, h.b2}) <= kEdge; }

bool share_a_vertex(const Triangle& p, const Triangle& q) {
  for (const Vec3f& u : {p.v0, p.v1, p.v2})
    for (const Vec3f& v : {q.v0, q.v1, q.v2})
      if (u == v) return true;
  return false;
}

/// Compares every ray with naive; reports the first few disagreements in full.
Agreement compare(std::span<const Triangle> tris, const EmbreeAccelerator& embree, const std::vector<Ray>& rays) {
  const NaiveAccelerator naive(tris);
  Agreement s;
  for (const Ray& r : rays) {
    ++s.rays;
    const auto a = naive.closest_hit(r);
    const auto b = embree.closest_hit(r);
    const bool any_same = naive.any_hit(r) == embree.any_hit(r);
    s.any_differs += !any_same;
    s.hits += a.has_value();
    bool ok = any_same;
    if (a && b && a->triangle == b->triangle) {
      const double rel_t = std::abs(double(b->t) - double(a->t)) / double(a->t);
      s.max_rel_t = std::max(s.max_rel_t, rel_t);
      s.max_bary = std::max({s.max_bary, double(std::abs(a->b0 - b->b0)), double(std::abs(a->b1 - b->b1)),
                             double(std::abs(a->b2 - b->b2))});
      ok = ok && rel_t <= kRelT;
    } else if (a || b) {
      // A tie: the same t, and naive also finds Embree's triangle there
      // (overlaps), or the two share a vertex or edge the ray went through
      // (naive's watertight test gives a shared edge to one of them only).
      bool tie = false;
      if (a && b && std::abs(double(b->t) - double(a->t)) <= kRelT * double(a->t)) {
        float t, b0, b1, b2;
        tie = on_edge(*b) || share_a_vertex(tris[a->triangle], tris[b->triangle]) ||
              (intersect_triangle(PreparedRay(r), tris[b->triangle], r.tmin, r.tmax, t, b0, b1, b2) &&
               std::abs(double(t) - double(a->t)) <= kRelT * double(a->t));
      }
      // A graze: the nearer answer is on an edge or vertex of its triangle
      // (a silhouette), which the other test judged a miss; then any_hit may
      // differ too.
      const Hit& nearer = !b || (a && a->t < b->t) ? *a : *b;
      const bool graze = !tie && on_edge(nearer);
      s.ties += tie && any_same;
      s.grazes += graze;
      ok = (tie && any_same) || graze;
    }
    if (!ok && ++s.mismatches <= 3) ADD_FAILURE() << describe(r, a, b);
  }
  return s;
}

void print(const char* what, const Agreement& s) {
  std::printf("[ embree   ] %-26s %5zu rays %5zu hits: ties %4zu grazes %3zu (%.1e of hits), any_hit differs %zu; "
              "max rel t %.1e, max bary %.1e\n",
              what, s.rays, s.hits, s.ties, s.grazes, s.hits ? double(s.ties + s.grazes) / double(s.hits) : 0.0,
              s.any_differs, s.max_rel_t, s.max_bary);
}

Bounds3f bounds_of(std::span<const Triangle> tris) {
  Bounds3f b;
  for (const Triangle& t : tris)
    for (const Vec3f& v : {t.v0, t.v1, t.v2})
      if (is_finite(v)) b.extend(v);
  return b;
}

/// Random rays from inside and around the bounding box, some with a finite
/// tmax or a tmin > 0. Ties among these are chance events.
std::vector<Ray> random_rays(std::span<const Triangle> tris, std::size_t n, std::uint32_t seed) {
  const Bounds3f box = bounds_of(tris);
  const Vec3f size = box.hi - box.lo;
  const float diagonal = length(size);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f), wide(-0.5f, 1.5f);
  std::normal_distribution<float> g;
  std::vector<Ray> rays;
  for (std::size_t i = 0; i < n; ++i) {
    const bool inside = i % 2 == 0;
    const Vec3f f = inside ? Vec3f{u(rng), u(rng), u(rng)} : Vec3f{wide(rng), wide(rng), wide(rng)};
    Ray r{box.lo + Vec3f{f.x * size.x, f.y * size.y, f.z * size.z}, {g(rng), g(rng), g(rng)}};
    if (i % 5 == 3) r.tmax = u(rng) * diagonal;
    if (i % 5 == 4) r.tmin = u(rng) * 0.3f * diagonal;
    rays.push_back(r);
  }
  return rays;
}

/// Rays aimed at vertices and edge midpoints: ties on purpose.
std::vector<Ray> tie_rays(std::span<const Triangle> tris, std::size_t n, std::uint32_t seed) {
  const Bounds3f box = bounds_of(tris);
  const Vec3f size = box.hi - box.lo;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> wide(-0.5f, 1.5f);
  std::uniform_int_distribution<std::size_t> pick(0, tris.size() - 1);
  std::vector<Ray> rays;
  for (std::size_t i = 0; i < n; ++i) {
    const Triangle& t = tris[pick(rng)];
    const Vec3f target = i % 2 ? t.v0 : (t.v0 + t.v1) * 0.5f;
    const Vec3f o = box.lo + Vec3f{wide(rng) * size.x, wide(rng) * size.y, wide(rng) * size.z};
    if (!(o == target)) rays.push_back({o, target - o});
  }
  return rays;
}

/// Random rays: no mismatch, the same any_hit, and ties plus grazes at most 1
/// in 1000 hits. Rays aimed at vertices and edges: ties and grazes are
/// expected there, but each must be a genuine one.
void expect_agreement(const char* what, std::span<const Triangle> tris, std::size_t random, std::size_t aimed,
                      EmbreeMode mode = EmbreeMode::robust) {
  const EmbreeAccelerator embree(tris, nullptr, false, mode);
  std::printf("[ embree   ] %s: %zu triangles, %.2f MiB, built in %.1f ms\n", what, tris.size(),
              double(embree.bytes()) / double(1 << 20), embree.build_s() * 1e3);
  const Agreement r = compare(tris, embree, random_rays(tris, random, 1));
  print((std::string(what) + " random").c_str(), r);
  EXPECT_EQ(r.mismatches, 0u) << what;
  EXPECT_EQ(r.any_differs, 0u) << what;
  EXPECT_LE(double(r.ties + r.grazes), 1e-3 * double(r.hits)) << what;
  EXPECT_GE(r.hits, 50u) << what << ": too few rays hit anything to compare";
  const Agreement a = compare(tris, embree, tie_rays(tris, aimed, 2));
  print((std::string(what) + " at vertices/edges").c_str(), a);
  EXPECT_EQ(a.mismatches, 0u) << what;
}

TEST(Embree, AnalyticTriangleGivesExactTAndBarycentrics) {
  const std::vector<Triangle> tri = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
  const EmbreeAccelerator embree(tri);
  for (const float len : {1.0f, 2.0f, 0.25f}) {  // t is in units of |d|
    const Ray ray{{0.25f, 0.5f, 1.0f}, {0, 0, -len}};
    const auto hit = embree.closest_hit(ray);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->triangle, 0u);
    EXPECT_NEAR(hit->t, 1.0f / len, 1e-6f / len);
    EXPECT_NEAR(hit->b0, 0.25f, 1e-6f);  // weight of v0 = (0,0,0)
    EXPECT_NEAR(hit->b1, 0.25f, 1e-6f);  // weight of v1 = (1,0,0): x
    EXPECT_NEAR(hit->b2, 0.5f, 1e-6f);   // weight of v2 = (0,1,0): y
    // Kappa's segment is (tmin, tmax]: a hit at exactly tmax counts, at tmin not.
    EXPECT_TRUE(embree.closest_hit(Ray{ray.o, ray.d, 0.0f, hit->t}));
    EXPECT_TRUE(embree.any_hit(Ray{ray.o, ray.d, 0.0f, hit->t}));
    EXPECT_FALSE(embree.closest_hit(Ray{ray.o, ray.d, hit->t}));
    EXPECT_FALSE(embree.any_hit(Ray{ray.o, ray.d, hit->t}));
    EXPECT_FALSE(embree.closest_hit(Ray{ray.o, ray.d, 0.0f, next_float_down(hit->t)}));
  }
  EXPECT_FALSE(embree.closest_hit(Ray{{0.75f, 0.5f, 1.0f}, {0, 0, -1}}));  // outside the hypotenuse
}

TEST(Embree, BuildLeavesTheCallersFloatingPointModeAlone) {
  // Embree's build runs with flush-to-zero and denormals-are-zero. TBB must
  // not capture those for this thread's later parallel_for (the render): the
  // renderer's arithmetic would change. Meaningful when this test runs in a
  // fresh process, as CTest runs it.
  constexpr unsigned kFtzDaz = 0x8040;
  const unsigned before = _mm_getcsr() & kFtzDaz;
  const auto tris = test::random_soup(1000, 11);
  const EmbreeAccelerator embree(tris);
  EXPECT_EQ(_mm_getcsr() & kFtzDaz, before);
  std::atomic<unsigned> in_tasks{0};
  tbb::parallel_for(0, 64, [&](int) { in_tasks |= _mm_getcsr() & kFtzDaz; });
  EXPECT_EQ(in_tasks.load(), before);
}

TEST(Embree, RayLeavingASurfaceFromOnItDoesNotHitIt) {
  // The renderer's offset origin lies exactly on an axis-aligned plane at 0
  // (no rounding error to step over), so the hit there is at t = 0, which
  // Kappa's (tmin, tmax] excludes, also with denormals-are-zero on (a
  // denormal tnear would then read as 0).
  const std::vector<Triangle> floor = {{{552.8f, 0, 0}, {0, 0, 0}, {0, 0, 559.2f}},
                                       {{552.8f, 0, 0}, {0, 0, 559.2f}, {549.6f, 0, 559.2f}}};
  const EmbreeAccelerator embree(floor);
  const unsigned csr = _mm_getcsr();
  for (const unsigned mode : {csr, csr | 0x8040u}) {
    _mm_setcsr(mode);
    for (const Vec3f d : {Vec3f{-0.98f, 0.1f, 0.14f}, Vec3f{0.02f, 0.96f, 0.29f}, Vec3f{0.3f, -0.9f, 0.1f}}) {
      EXPECT_FALSE(embree.closest_hit(Ray{{273.46231f, 0, 86.007416f}, d})) << std::hex << mode;
      EXPECT_FALSE(embree.any_hit(Ray{{273.46231f, 0, 86.007416f}, d})) << std::hex << mode;
    }
  }
  _mm_setcsr(csr);
}

TEST(Embree, RandomSoupsAgreeWithNaive) {
  for (std::size_t n : {1, 10, 100, 1000, 10000}) {
    const auto tris = test::random_soup(n, std::uint32_t(n), n < 100 ? 0.5f : 0.1f);
    expect_agreement(("soup " + std::to_string(n)).c_str(), tris, n < 1000 ? 3000 : 1500, 1000);
  }
}

TEST(Embree, LowResolutionBunnyAgreesWithNaive) {
  const auto tris = test::load_mesh(test::assets_dir() / "bunny-lowres" / "bunny_lowres.obj");
  ASSERT_EQ(tris.size(), 3674u);
  expect_agreement("bunny-lowres", tris, 8000, 2000);
}

TEST(Embree, FullBunnyFromSharedScenesAgreesWithNaive) {
  const auto shared = test::shared_scenes_dir();
  if (shared.empty()) GTEST_SKIP() << "../shared/scenes not present (a user's clone): skipping the 69k-triangle bunny";
  const auto tris = test::load_mesh(shared / "bunny" / "bunny.obj");
  expect_agreement("bunny", tris, 800, 300);
}

// Embree without the robust flag, at high build quality (spatial splits): the
// same agreement with naive on random rays, to rounding, and only genuine
// ties and grazes at vertices and edges (its Moeller test may let a ray
// through an edge, which counts as a graze of naive's hit).
TEST(Embree, FastModeAgreesWithNaiveToRounding) {
  for (std::size_t n : {1, 10, 1000, 10000}) {
    const auto tris = test::random_soup(n, std::uint32_t(n), n < 100 ? 0.5f : 0.1f);
    expect_agreement(("fast soup " + std::to_string(n)).c_str(), tris, n < 1000 ? 3000 : 1500, 500, EmbreeMode::fast);
  }
  const auto bunny = test::load_mesh(test::assets_dir() / "bunny-lowres" / "bunny_lowres.obj");
  expect_agreement("fast bunny-lowres", bunny, 4000, 1000, EmbreeMode::fast);
}

TEST(Embree, ClosedBoxIsWatertight) {
  // Robust mode: rays from inside a closed box all hit, also through its
  // edges and corners, as naive's do.
  Scene room;
  test::add_box(room, {0, 0, 0}, {556, 548.8f, 559.2f}, true, 0);
  const EmbreeAccelerator embree(room.triangles);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::normal_distribution<float> n;
  for (int i = 0; i < 20000; ++i) {
    const Vec3f o{u(rng) * 556, u(rng) * 548.8f, u(rng) * 559.2f};
    ASSERT_TRUE(embree.closest_hit(Ray{o, {n(rng), n(rng), n(rng)}}));
  }
  const Agreement a = compare(room.triangles, embree, tie_rays(room.triangles, 2000, 4));
  print("box at vertices/edges", a);
  EXPECT_EQ(a.mismatches, 0u);
}

TEST(Embree, DegenerateTrianglesAreNeverHitAndIdsStayPut) {
  auto tris = test::random_soup(300, 5, 0.2f);
  tris.insert(tris.begin() + 10, Triangle{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}});  // collinear
  tris.insert(tris.begin() + 20, Triangle{{0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}, {0, 1, 0}});  // repeated vertex
  tris.push_back({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}});
  tris.push_back({{NAN, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const EmbreeAccelerator embree(tris);
  EXPECT_EQ(embree.degenerate(), 4u);
  // Rays straight at the degenerate ones, from all around.
  std::mt19937 rng(6);
  std::normal_distribution<float> n;
  for (const Vec3f target : {Vec3f{1, 1, 1}, Vec3f{0.25f, 0.75f, 0.25f}, Vec3f{0, 0, 0}}) {
    for (int i = 0; i < 1000; ++i) {
      const Vec3f d{n(rng), n(rng), n(rng)};
      const auto hit = embree.closest_hit(Ray{target - d, d});
      if (hit) {
        EXPECT_TRUE(hit->triangle != 10 && hit->triangle != 20 && hit->triangle < 302) << hit->triangle;
      }
    }
  }
  const Agreement r = compare(tris, embree, random_rays(tris, 3000, 7));
  EXPECT_EQ(r.mismatches, 0u);
}

TEST(Embree, EmptySceneMissesAndNonFiniteRaysMiss) {
  const EmbreeAccelerator empty(std::span<const Triangle>{});
  EXPECT_FALSE(empty.closest_hit(Ray{{0, 0, 0}, {0, 0, 1}}));
  EXPECT_FALSE(empty.any_hit(Ray{{0, 0, 0}, {0, 0, 1}}));
  // One large triangle that the finite ray does hit: each non-finite variant
  // of it must miss.
  const std::vector<Triangle> tris = {{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}};
  const EmbreeAccelerator embree(tris);
  ASSERT_TRUE(embree.closest_hit(Ray{{0, 0, -5}, {0, 0, 1}}));
  for (const Ray& r : {Ray{{NAN, 0, -5}, {0, 0, 1}}, Ray{{0, 0, -INFINITY}, {0, 0, 1}}, Ray{{0, 0, -5}, {0, 0, INFINITY}},
                       Ray{{0, 0, -5}, {0, 0, 0}}, Ray{{0, 0, -5}, {0, 0, 1}, NAN}, Ray{{0, 0, -5}, {0, 0, 1}, 0, NAN}}) {
    EXPECT_FALSE(embree.closest_hit(r));
    EXPECT_FALSE(embree.any_hit(r));
  }
}

TEST(Embree, ParallelQueriesMatchSerialOnes) {
  const auto tris = test::load_mesh(test::assets_dir() / "bunny-lowres" / "bunny_lowres.obj");
  const EmbreeAccelerator embree(tris);
  const auto rays = random_rays(tris, 20000, 9);
  std::vector<Hit> serial(rays.size()), parallel(rays.size());
  std::vector<char> occluded(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) serial[i] = embree.closest_hit(rays[i]).value_or(Hit{});
  tbb::parallel_for(std::size_t(0), rays.size(), [&](std::size_t i) {
    parallel[i] = embree.closest_hit(rays[i]).value_or(Hit{});
    occluded[i] = embree.any_hit(rays[i]);
  });
  for (std::size_t i = 0; i < rays.size(); ++i) {
    ASSERT_EQ(parallel[i].triangle, serial[i].triangle) << i;
    ASSERT_EQ(parallel[i].t, serial[i].t) << i;
    ASSERT_EQ(bool(occluded[i]), serial[i].valid()) << i;
  }
}

TEST(Embree, FactoryNamesItAndReportsMemoryAndBuildTime) {
  const auto names = accelerator_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "embree"), names.end());
  const auto tris = test::random_soup(1000, 10);
  const auto accel = make_accelerator("embree", tris);
  EXPECT_EQ(accel->name(), "embree");
  const Accelerator& embree = *accel;  // through the interface, as reports read it
  EXPECT_EQ(embree.kind(), AccelKind::embree);
  EXPECT_EQ(embree.cells(), nullptr);
  // At least its own copy of the vertices (36 B) and indices (12 B) per triangle.
  EXPECT_GE(embree.bytes(), 48u * tris.size());
  EXPECT_LT(embree.bytes(), 10000u * tris.size());
  EXPECT_GT(embree.build_s(), 0.0);
  // The other mode, by its own name.
  EXPECT_NE(std::find(names.begin(), names.end(), "embree-fast"), names.end());
  const auto fast = make_accelerator("embree-fast", tris);
  EXPECT_EQ(fast->name(), "embree-fast");
  EXPECT_EQ(fast->kind(), AccelKind::embree);
  EXPECT_EQ(static_cast<const EmbreeAccelerator&>(*fast).mode(), EmbreeMode::fast);
  EXPECT_GE(fast->bytes(), 48u * tris.size());
  std::printf("[ embree   ] 1000-triangle soup: %llu bytes, build %.2f ms\n",
              static_cast<unsigned long long>(embree.bytes()), embree.build_s() * 1e3);
}

/// Images with embree and grid, same seed. Metric: the mean absolute pixel
/// difference relative to the image mean, sum|e - g| / sum g over all pixels
/// and channels. Hits differ only in rounding, so paths mostly coincide and it
/// must stay far below the same metric between two seeds (pure noise); and
/// each channel's mean must agree within 3 standard errors of the mean of
/// the paired per-pixel differences (the same seed makes the two images'
/// noise largely shared, which independent standard errors would ignore).
void expect_same_image_as_grid(const std::filesystem::path& scene_file, int size, int spp) {
  Warnings warnings;
  Scene scene = load_scene(scene_file, warnings);
  scene.width = scene.height = size;
  RenderSettings settings;
  settings.spp = spp;
  const Film embree = test::render_scene(scene, settings, "embree");
  const Film grid = test::render_scene(scene, settings, "grid");
  settings.seed = 1;
  const Film other_seed = test::render_scene(scene, settings, "grid");
  auto rel_mad = [](const Film& a, const Film& b) {
    double diff = 0, sum = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) diff += std::abs(a.rgb[i] - b.rgb[i]), sum += b.rgb[i];
    return diff / sum;
  };
  const double mad = rel_mad(embree, grid), noise = rel_mad(other_seed, grid);
  std::printf("[ embree   ] %s: relative MAD embree/grid %.3e, between seeds %.3e\n",
              scene_file.parent_path().filename().c_str(), mad, noise);
  EXPECT_LT(mad, 0.01 * noise) << scene_file;
  for (int c = 0; c < 3; ++c) {
    double sum = 0, sum2 = 0;
    const std::size_t n = embree.pixels();
    for (std::size_t i = 0; i < n; ++i) {
      const double d = double(embree.rgb[3 * i + std::size_t(c)]) - double(grid.rgb[3 * i + std::size_t(c)]);
      sum += d, sum2 += d * d;
    }
    const double mean = sum / double(n);
    const double se = std::sqrt(std::max(0.0, sum2 / double(n) - mean * mean) / double(n));
    // Identical images (se = 0) must agree exactly; otherwise within 3 SE.
    EXPECT_LE(std::abs(mean), 3 * se) << "channel " << c << ": mean paired difference " << mean << ", SE " << se;
  }
}

TEST(Embree, CornellBoxImageAgreesWithGrid) {
  expect_same_image_as_grid(test::assets_dir() / "cornell-box" / "scene.json", 64, 16);
}

TEST(Embree, LowResolutionBunnyImageAgreesWithGrid) {
  expect_same_image_as_grid(test::assets_dir() / "bunny-lowres" / "scene_lowres.json", 64, 8);
}

}  // namespace
}  // namespace kappa
