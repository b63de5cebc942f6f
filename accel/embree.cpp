#include "embree.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "core/float_util.h"
#include "core/parallel.h"

namespace kappa {
namespace {

const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_UNKNOWN: return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
  }
  return "error";
}

/// Errors must be one line (the CLI prints them as the whole diagnostic).
std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

/// Rays naive can never hit with: Embree does not promise anything for them
/// (this build does not ignore invalid rays), so they miss before reaching it.
bool queryable(const Ray& r) {
  return is_finite(r.o) && is_finite(r.d) && !(r.d.x == 0 && r.d.y == 0 && r.d.z == 0) && !std::isnan(r.tmin) &&
         !std::isnan(r.tmax) && r.tmin < r.tmax;
}

void to_embree(const Ray& r, RTCRay& e) {
  e.org_x = r.o.x, e.org_y = r.o.y, e.org_z = r.o.z;
  // Embree accepts t in [tnear, tfar]; Kappa's segment is (tmin, tmax]. In
  // float the two are the same set once tnear is the next float above tmin.
  // Never below the smallest normal float, though: with denormals-are-zero
  // on (Embree's own recommendation) a denormal tnear reads as 0 and a ray
  // leaving a surface from exactly on it (t = 0) would hit that surface.
  // Naive never returns t <= 0 either.
  e.tnear = std::max(next_float_up(r.tmin), std::numeric_limits<float>::min());
  e.dir_x = r.d.x, e.dir_y = r.d.y, e.dir_z = r.d.z;
  e.time = 0;
  e.tfar = r.tmax;
  e.mask = 0xFFFFFFFFu;  // this build has ray masks on: a zero mask would hit nothing
  e.id = 0;
  e.flags = 0;
}

/// An intersect context that carries the query's hit filter to the
/// geometry's filter callback (Embree passes the context through).
struct FilterContext {
  RTCIntersectContext embree;  // first: Embree sees a pointer to it
  const FunctionHitFilter* filter = nullptr;
};

/// The geometry's intersection and occlusion filter: a candidate the query's
/// filter refuses is as if the triangle were not there (valid = 0).
void filter_candidates(const RTCFilterFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const FilterContext*>(args->context);
  if (!context->filter) return;  // an unfiltered query on a filtered build
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    const Hit candidate{RTCHitN_primID(args->hit, args->N, i), RTCRayN_tfar(args->ray, args->N, i), 1.0f - u - v, u, v};
    if (!context->filter->accepts(candidate)) args->valid[i] = 0;
  }
}

}  // namespace

EmbreeAccelerator::EmbreeAccelerator(std::span<const Triangle> triangles, TaskProgress* progress, bool filtered,
                                     EmbreeMode mode)
    : m_filtered(filtered), m_mode(mode) {
  const auto start = std::chrono::steady_clock::now();
  m_device = rtcNewDevice(nullptr);
  if (!m_device) {
    throw std::runtime_error(std::string("embree: cannot create a device: ") + error_name(rtcGetDeviceError(nullptr)));
  }
  rtcSetDeviceErrorFunction(m_device, &on_error, this);
  rtcSetDeviceMemoryMonitorFunction(m_device, &on_memory, this);
  try {
    // One vertex triple per triangle keeps primID == TriangleId without a
    // lookup table; 3 N must fit Embree's 32-bit indices.
    if (triangles.size() > std::numeric_limits<std::uint32_t>::max() / 3)
      throw std::runtime_error("embree: " + std::to_string(triangles.size()) + " triangles exceed 32-bit indices");
    m_scene = rtcNewScene(m_device);
    // Robust mode: the watertight triangle test, and no rays slipping
    // between triangles that share an edge. Fast mode: Embree's defaults
    // but the build quality, high for spatial splits (embree.h).
    rtcSetSceneFlags(m_scene, mode == EmbreeMode::robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
    rtcSetSceneBuildQuality(m_scene, RTC_BUILD_QUALITY_HIGH);
    check("creating the scene");
    // An empty scene is simply committed with no geometry: every query misses
    // (Embree refuses zero-sized buffers).
    if (!triangles.empty()) {
      const RTCGeometry geometry = rtcNewGeometry(m_device, RTC_GEOMETRY_TYPE_TRIANGLE);
      const std::size_t n = triangles.size();
      // rtcSetNewGeometryBuffer pads the vertex buffer for Embree's 16-byte
      // loads, which a buffer shared straight from the span would not be.
      auto* vertices = static_cast<float*>(
          rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
      auto* indices = static_cast<std::uint32_t*>(
          rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), n));
      if (vertices && indices) {
        static_assert(sizeof(Triangle) == 9 * sizeof(float));
        std::memcpy(vertices, triangles.data(), n * sizeof(Triangle));
        const float nan = std::numeric_limits<float>::quiet_NaN();
        for (std::size_t i = 0; i < n; ++i) {
          indices[3 * i] = std::uint32_t(3 * i), indices[3 * i + 1] = std::uint32_t(3 * i + 1);
          indices[3 * i + 2] = std::uint32_t(3 * i + 2);
          // Zero-area triangles can pass a float test after rounding; naive
          // and grid leave them out, so Embree must too. Embree's build skips
          // triangles with non-finite vertices: NaN makes them unhittable
          // while every other id stays where it is.
          const double area = double_area(triangles[i]);
          if (!(area > 0) || !std::isfinite(area)) {
            std::fill(vertices + 9 * i, vertices + 9 * i + 9, nan);
            ++m_degenerate;
          }
        }
      }
      rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
      if (filtered) {
        // Only a build that will be asked filtered queries pays for the
        // callback on every candidate hit.
        rtcSetGeometryIntersectFilterFunction(geometry, &filter_candidates);
        rtcSetGeometryOccludedFilterFunction(geometry, &filter_candidates);
      }
      rtcCommitGeometry(geometry);
      rtcAttachGeometry(m_scene, geometry);  // geomID 0
      rtcReleaseGeometry(geometry);  // the scene keeps its own reference
      check("creating the triangle geometry");
    }
    // rtcCommitScene turns on flush-to-zero and denormals-are-zero for its
    // TBB build tasks. If this thread has not used TBB yet, TBB creates its
    // default task context right then and captures those settings, and every
    // later parallel_for from this thread (the whole render) would run with
    // them. A no-op TBB loop first makes TBB capture the caller's own (TBB's
    // own, not kappa::parallel_for, which a TSan build runs on std::threads).
    tbb::parallel_for(0, 1, [](int) {});
    if (progress) {
      progress->begin("embree: building the BVH", 1000);
      rtcSetSceneProgressMonitorFunction(
          m_scene,
          [](void* task, double fraction) {
            static_cast<TaskProgress*>(task)->set(std::uint64_t(fraction * 1000), 1000);
            tbb_release();  // Embree's TBB workers call this (parallel.h)
            return true;    // never cancel
          },
          progress);
    }
    rtcCommitScene(m_scene);
    tbb_acquire();  // its workers' writes (the progress callback's) come before this (parallel.h)
    if (progress) rtcSetSceneProgressMonitorFunction(m_scene, nullptr, nullptr);  // `progress` dies after the build
    check("building the BVH");
  } catch (...) {
    if (m_scene) rtcReleaseScene(m_scene);
    rtcReleaseDevice(m_device);
    throw;
  }
  m_build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

EmbreeAccelerator::~EmbreeAccelerator() {
  rtcReleaseScene(m_scene);
  rtcReleaseDevice(m_device);
}

void EmbreeAccelerator::on_error(void* self, RTCError code, const char* message) {
  // Called from inside Embree, maybe on a TBB worker: record, never throw.
  auto* a = static_cast<EmbreeAccelerator*>(self);
  const std::lock_guard lock(a->m_error_mutex);
  if (a->m_error.empty()) a->m_error = std::string(error_name(code)) + (message ? std::string(": ") + message : "");
}

bool EmbreeAccelerator::on_memory(void* self, ssize_t bytes, bool /*post*/) {
  // Allocations are reported with bytes > 0, frees with bytes < 0, possibly
  // from several build threads at once.
  static_cast<EmbreeAccelerator*>(self)->m_bytes += std::int64_t(bytes);
  return true;  // never refuse: limits are not this accelerator's policy
}

void EmbreeAccelerator::check(const char* step) {
  const RTCError code = rtcGetDeviceError(m_device);
  std::string error;
  {
    const std::lock_guard lock(m_error_mutex);
    error.swap(m_error);
  }
  if (error.empty() && code != RTC_ERROR_NONE) error = error_name(code);
  if (!error.empty()) throw std::runtime_error(one_line("embree: " + std::string(step) + ": " + error));
}

std::optional<Hit> EmbreeAccelerator::closest_hit(const Ray& ray) const { return closest(ray, nullptr); }

bool EmbreeAccelerator::any_hit(const Ray& ray) const { return any(ray, nullptr); }

std::optional<Hit> EmbreeAccelerator::closest_hit(const Ray& ray, const FunctionHitFilter& filter) const {
  if (!m_filtered) throw std::logic_error("embree: a filtered query on a build without its filter callback");
  return closest(ray, &filter);
}

bool EmbreeAccelerator::any_hit(const Ray& ray, const FunctionHitFilter& filter) const {
  if (!m_filtered) throw std::logic_error("embree: a filtered query on a build without its filter callback");
  return any(ray, &filter);
}

std::optional<Hit> EmbreeAccelerator::closest(const Ray& ray, const FunctionHitFilter* filter) const {
  if (!queryable(ray)) return std::nullopt;
  FilterContext context;  // per query, on the stack: queries share nothing
  rtcInitIntersectContext(&context.embree);
  context.filter = filter;
  RTCRayHit rh;
  to_embree(ray, rh.ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(m_scene, &context.embree, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  // Embree's u, v weight v1 and v2; Kappa's b0, b1, b2 weight v0, v1, v2.
  return Hit{rh.hit.primID, rh.ray.tfar, 1.0f - rh.hit.u - rh.hit.v, rh.hit.u, rh.hit.v};
}

bool EmbreeAccelerator::any(const Ray& ray, const FunctionHitFilter* filter) const {
  if (!queryable(ray)) return false;
  FilterContext context;
  rtcInitIntersectContext(&context.embree);
  context.filter = filter;
  RTCRay r;
  to_embree(ray, r);
  rtcOccluded1(m_scene, &context.embree, &r);
  return r.tfar == -std::numeric_limits<float>::infinity();  // Embree's mark for "occluded"
}

}  // namespace kappa
