// What every exact accelerator is held to: bitwise naive's closest hit
// (triangle id, t, barycentrics) and its occlusion answer, on ray families
// built from the accelerator's own cell planes. Shared by the suite
// parametrised over the exact accelerators (exact_agreement_test.cpp) and by
// each accelerator's own tests.
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "accel/cell_layout.h"
#include "accel/naive.h"

namespace kappa::test {

using Rays = std::vector<Ray>;

/// Compares every ray; reports the first few disagreements in full.
inline void expect_agreement(std::span<const Triangle> tris, const Accelerator& accel, const Rays& rays) {
  const NaiveAccelerator naive(tris);
  std::size_t mismatches = 0, hits = 0;
  for (const Ray& r : rays) {
    const auto a = naive.closest_hit(r);
    const auto b = accel.closest_hit(r);
    const bool occluded_a = naive.any_hit(r), occluded_b = accel.any_hit(r);
    hits += a.has_value();
    const bool same = a.has_value() == b.has_value() && occluded_a == occluded_b &&
                      (!a || (a->triangle == b->triangle && std::bit_cast<std::uint32_t>(a->t) ==
                                                                  std::bit_cast<std::uint32_t>(b->t) &&
                              std::bit_cast<std::uint32_t>(a->b0) == std::bit_cast<std::uint32_t>(b->b0) &&
                              std::bit_cast<std::uint32_t>(a->b1) == std::bit_cast<std::uint32_t>(b->b1) &&
                              std::bit_cast<std::uint32_t>(a->b2) == std::bit_cast<std::uint32_t>(b->b2)));
    if (!same && ++mismatches <= 3) {
      const CellLayout* cells = accel.cells();
      ADD_FAILURE() << "ray o=(" << r.o.x << "," << r.o.y << "," << r.o.z << ") d=(" << r.d.x << "," << r.d.y << ","
                    << r.d.z << ") tmin=" << r.tmin << " tmax=" << r.tmax << ": naive "
                    << (a ? std::to_string(a->triangle) + " t=" + std::to_string(a->t) : std::string("miss"))
                    << " any=" << occluded_a << ", " << accel.name() << " "
                    << (b ? std::to_string(b->triangle) + " t=" + std::to_string(b->t) : std::string("miss"))
                    << " any=" << occluded_b << " (" << (cells ? cells->resolution_text() : std::string()) << ")";
    }
  }
  EXPECT_EQ(mismatches, 0u) << "of " << rays.size() << " rays (" << hits << " hits)";
}

inline Vec3f lerp(const Vec3d& a, const Vec3d& b, double t) { return Vec3f(a + (b - a) * t); }

/// The ray families an exact accelerator must get right: random rays from
/// inside and around the box, axis-parallel rays (with -0), rays lying in
/// cell planes and along cell edges, rays through cell vertices, rays
/// starting on the box's faces, finite tmax and tmin > 0. Planes come from
/// the accelerator's cells (any cell's faces, every level), or from a 16^3
/// split of the triangles' box for an accelerator without cells.
inline Rays ray_families(std::span<const Triangle> tris, const Accelerator& accel, std::size_t per_family,
                         std::uint32_t seed) {
  const CellLayout* cells = accel.cells();
  Vec3d lo{1e30, 1e30, 1e30}, hi{-1e30, -1e30, -1e30};
  if (cells) {
    lo = cells->bounds().lo, hi = cells->bounds().hi;
  } else {
    for (const Triangle& t : tris)
      for (const Vec3f& v : {t.v0, t.v1, t.v2}) lo = min(lo, Vec3d(v)), hi = max(hi, Vec3d(v));
    if (tris.empty()) lo = Vec3d{-1, -1, -1}, hi = Vec3d{1, 1, 1};
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), wide(-0.5, 1.5);
  auto inside = [&] { return lerp(lo, hi, 0.0) + Vec3f(Vec3d{u(rng), u(rng), u(rng)} * (hi - lo)); };
  auto around = [&] { return Vec3f(lo + Vec3d{wide(rng), wide(rng), wide(rng)} * (hi - lo)); };
  auto direction = [&] {
    std::normal_distribution<float> n;
    return Vec3f{n(rng), n(rng), n(rng)};
  };
  auto plane = [&](int axis) {  // a face of a random cell, including the box faces
    if (!cells) return float(lo[axis] + std::uniform_int_distribution<int>(0, 16)(rng) * (hi[axis] - lo[axis]) / 16);
    const std::uint64_t i = std::uniform_int_distribution<std::uint64_t>(0, cells->cell_count() - 1)(rng);
    const CellBox b = cells->cell_box(i);
    return float(u(rng) < 0.5 ? b.lo[axis] : b.hi[axis]);
  };
  auto cell_vertex = [&] { return Vec3f{plane(0), plane(1), plane(2)}; };
  const Vec3f axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

  Rays rays;
  for (std::size_t i = 0; i < per_family; ++i) {
    rays.push_back({inside(), direction()});
    rays.push_back({around(), direction()});
    Vec3f d = axes[i % 6];
    if (i % 12 >= 6) d = Vec3f{d.x == 0 ? -0.0f : d.x, d.y == 0 ? -0.0f : d.y, d.z == 0 ? -0.0f : d.z};
    rays.push_back({around(), d});
    {
      const int axis = int(i % 3);
      Vec3f o = around();
      Vec3f dir = direction();
      (axis == 0 ? o.x : axis == 1 ? o.y : o.z) = plane(axis);
      (axis == 0 ? dir.x : axis == 1 ? dir.y : dir.z) = 0.0f;
      rays.push_back({o, dir});
      Vec3f e = around();
      const int a1 = (axis + 1) % 3;
      (axis == 0 ? e.x : axis == 1 ? e.y : e.z) = plane(axis);
      (a1 == 0 ? e.x : a1 == 1 ? e.y : e.z) = plane(a1);
      rays.push_back({e, axes[2 * ((axis + 2) % 3)] * (i % 2 ? 1.0f : -1.0f)});
    }
    {
      const Vec3f o = i % 2 ? inside() : around();
      const Vec3f target = cell_vertex();
      if (!(target == o)) rays.push_back({o, target - o});
    }
    {
      Vec3f o = inside();
      const int axis = int(i % 3);
      (axis == 0 ? o.x : axis == 1 ? o.y : o.z) = float(i % 2 ? lo[axis] : hi[axis]);
      rays.push_back({o, direction()});
    }
    {
      Ray r{around(), direction()};
      r.tmax = float(u(rng) * length(hi - lo));
      rays.push_back(r);
      Ray s{inside(), direction()};
      s.tmin = float(u(rng) * 0.3 * length(hi - lo));
      rays.push_back(s);
    }
  }
  return rays;
}

/// Rays from random points of [-3, 3]^3 aimed exactly at the vertices and
/// edge midpoints of `tris`: they meet several triangles at (nearly) equal
/// t, so the tie rule must decide, not the order in which cells are tested.
inline Rays rays_at_vertices(std::span<const Triangle> tris, std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  Rays rays;
  for (std::size_t i = 0; i < n; ++i) {
    const Triangle& t = tris[i % tris.size()];
    const Vec3f target = i % 3 == 0 ? t.v0 : i % 3 == 1 ? t.v1 : (t.v1 + t.v2) * 0.5f;
    const Vec3f o{u(rng), u(rng), u(rng)};
    if (!(target == o)) rays.push_back({o, target - o});
  }
  return rays;
}

}  // namespace kappa::test
