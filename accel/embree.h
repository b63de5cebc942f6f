// Intel Embree 3 as the reference accelerator, in two modes:
//   embree       robust mode (RTC_SCENE_FLAG_ROBUST): its watertight Pluecker
//                test on triangles stored with their vertices (Triangle4v),
//                in an SAH BVH *without* spatial splits: Embree 3.13 builds
//                robust scenes with its plain SAH builder at medium and high
//                quality alike (scene.cpp, createTriangleAccel);
//   embree-fast  Embree as a user gets it without the robust flag: the
//                Moeller test, not watertight (a ray may slip between two
//                triangles that share an edge), on Triangle4 leaves in an SAH
//                BVH with spatial splits (RTC_BUILD_QUALITY_HIGH).
// Both are peers to measure the grids against; neither is exact.
//
// Not bitwise naive: Embree has its own triangle tests (robust mode's is
// watertight), so t and barycentrics agree with naive's to float rounding,
// and where two triangles tie in t (shared edges and vertices, coplanar
// overlaps) it may return either one, not the lower id. Kappa's (tmin, tmax]
// is passed as Embree's closed [tnear, tfar] with tnear = the next float above
// tmin (and at least the smallest normal float), so a hit exactly at tmin, or
// at t = 0, is excluded as in Kappa. Unlike naive, Embree does not reject hits
// whose t > 0 is within rounding error of zero; the renderer's offset origins
// keep those from arising (the image tests check it).
#pragma once

#include <embree3/rtcore.h>

#include <atomic>
#include <cstdint>
#include <mutex>
#include <span>
#include <string>

#include "accel.h"
#include "core/task_progress.h"

namespace kappa {

/// Which Embree a build is (the comment above).
enum class EmbreeMode { robust, fast };

class EmbreeAccelerator final : public Accelerator {
 public:
  /// Builds the BVH. Throws std::runtime_error (one line) if Embree fails.
  /// Reports the BVH build to `progress`, if given, as a fraction of 1000.
  /// `filtered`: the geometry gets the filter callback that filtered
  /// queries need (AccelOptions::filtered); an unfiltered build refuses them.
  explicit EmbreeAccelerator(std::span<const Triangle> triangles, TaskProgress* progress = nullptr,
                             bool filtered = false, EmbreeMode mode = EmbreeMode::robust);
  ~EmbreeAccelerator() override;
  EmbreeAccelerator(const EmbreeAccelerator&) = delete;  // Embree holds `this` in its callbacks
  EmbreeAccelerator& operator=(const EmbreeAccelerator&) = delete;

  std::optional<Hit> closest_hit(const Ray& ray) const override;
  bool any_hit(const Ray& ray) const override;
  std::optional<Hit> closest_hit(const Ray& ray, const FunctionHitFilter& filter) const override;
  bool any_hit(const Ray& ray, const FunctionHitFilter& filter) const override;
  std::string_view name() const override { return m_mode == EmbreeMode::robust ? "embree" : "embree-fast"; }
  EmbreeMode mode() const { return m_mode; }
  AccelKind kind() const override { return AccelKind::embree; }

  /// Bytes Embree holds for this accelerator after the build (its copy of
  /// the vertices and indices plus the BVH), from its memory monitor.
  std::uint64_t bytes() const override { return std::uint64_t(m_bytes.load()); }
  /// Wall-clock seconds of the build (copy + rtcCommitScene).
  double build_s() const override { return m_build_s; }
  /// Zero-area or non-finite triangles kept out of the BVH (never hit).
  std::uint64_t degenerate() const { return m_degenerate; }

 private:
  static void on_error(void* self, RTCError code, const char* message);
  static bool on_memory(void* self, ssize_t bytes, bool post);
  std::optional<Hit> closest(const Ray& ray, const FunctionHitFilter* filter) const;
  bool any(const Ray& ray, const FunctionHitFilter* filter) const;
  /// Throws if Embree has reported an error since the last check.
  void check(const char* step);

  RTCDevice m_device = nullptr;
  RTCScene m_scene = nullptr;
  std::atomic<std::int64_t> m_bytes{0};  ///< net bytes allocated by m_device
  double m_build_s = 0;
  std::uint64_t m_degenerate = 0;
  bool m_filtered = false;
  EmbreeMode m_mode = EmbreeMode::robust;
  std::mutex m_error_mutex;  ///< the build reports errors from TBB workers
  std::string m_error;       ///< first error reported, "" if none
};

}  // namespace kappa
