// The integrator a frame runs, chosen once per frame from the scene and the
// settings (choose_path_variant) and compiled for each combination
// (kPathVariants): a scene without emitters does no light sampling, a closed
// scene (an environment of 0) no environment look-up, and a render without
// AOVs records no first hit. The general variant of a strategy keeps every
// branch behind run-time checks, as one integrator for all scenes would; it
// renders the same image bit for bit, which the tests check, and
// `--specialise off` selects it to measure what specialising saves.
//
// The surfaces are part of the choice too (SceneSurfaces): a scene whose
// materials are all Lambertian and that gives no vertex normals runs the
// Lambertian code of before materials existed (bitwise its images); vertex
// normals add the shading normal to it; any other material runs the general
// BSDF (renderer/bsdf/). The last two are compiled as the general variant of
// each strategy only (every light on, the first hit recorded), which keeps
// the build's size in check.
#pragma once

#include <array>
#include <string>
#include <utility>

#include "core/check.h"

namespace kappa {

/// How a path gathers light at each vertex (--light-sampling).
enum class LightSampling {
  mis,   ///< a light sample and the BSDF sample, weighted by the power heuristic
  nee,   ///< light samples only; BSDF-sampled rays count only emitters light sampling cannot pick
  bsdf,  ///< BSDF-sampled rays only: no shadow rays
};

/// "mis", "nee", "bsdf".
const char* light_sampling_name(LightSampling strategy);
/// The strategy of a --light-sampling name; throws InputError for another.
LightSampling parse_light_sampling(const std::string& name);

/// What a path's vertices scatter with.
enum class Surfaces : unsigned char {
  lambertian,         ///< albedo / pi about the geometric normal: the code before materials
  lambertian_smooth,  ///< albedo / pi about the shading normal (the mesh's vertex normals)
  general,            ///< the layered BSDF (renderer/bsdf/principled.h), shading normals
};

/// What one compiled integrator does. With `bsdf` there are no triangle
/// lights to sample; a scene with neither lights runs `bsdf` whatever was
/// asked (no light to sample, so every strategy is the same estimator).
struct PathVariant {
  LightSampling strategy = LightSampling::mis;
  bool triangle_lights = true;  ///< emissive triangles are sampled (next-event estimation)
  bool environment = true;      ///< rays that escape read the environment, which is also sampled unless bsdf
  bool aovs = true;             ///< the camera ray's first hit is recorded (albedo, normal, depth, cost AOVs)
  Surfaces surfaces = Surfaces::lambertian;
  /// What few scenes have: cut-outs (queries pass the any-hit filter), an
  /// environment image (sampled by its distribution) and punctual lights
  /// (glTF's point, spot and directional lights, found by light sampling
  /// only). Compiled only as each strategy's general variant on general
  /// surfaces, each behind a run-time check of whether the scene has it.
  bool extras = false;
};

/// Every variant the frames are compiled for: with AOVs and without, the
/// strategies with lights (mis and nee: triangles, environment or both),
/// bsdf (with and without the environment), on Lambertian surfaces; each
/// strategy's general variant (every light on, the first hit recorded) on
/// the other two kinds of surfaces; and on general surfaces with extras.
inline constexpr std::array<PathVariant, 25> kPathVariants = [] {
  std::array<PathVariant, 25> v{};
  std::size_t i = 0;
  for (bool aovs : {false, true}) {
    for (LightSampling s : {LightSampling::mis, LightSampling::nee})
      for (auto [t, e] : {std::pair{true, false}, std::pair{false, true}, std::pair{true, true}}) v[i++] = {s, t, e, aovs};
    v[i++] = {LightSampling::bsdf, false, false, aovs};
    v[i++] = {LightSampling::bsdf, false, true, aovs};
  }
  for (Surfaces k : {Surfaces::lambertian_smooth, Surfaces::general}) {
    v[i++] = {LightSampling::mis, true, true, true, k};
    v[i++] = {LightSampling::nee, true, true, true, k};
    v[i++] = {LightSampling::bsdf, false, true, true, k};
  }
  v[i++] = {LightSampling::mis, true, true, true, Surfaces::general, true};
  v[i++] = {LightSampling::nee, true, true, true, Surfaces::general, true};
  v[i++] = {LightSampling::bsdf, false, true, true, Surfaces::general, true};
  return v;
}();

/// What the scene has that a frame's integrator must handle.
struct SceneLighting {
  bool triangle_lights = false;    ///< emissive triangles bright enough to be lights (Lights::triangle_count)
  bool environment = false;        ///< a non-zero environment
  bool environment_light = false;  ///< one light sampling can pick (its power does not round to 0)
  bool environment_image = false;  ///< the environment is an image (EnvironmentMap)
  bool punctual_lights = false;    ///< glTF point, spot or directional lights (Scene::punctual_lights)
};

/// What the scene's surfaces need (Scene::materials, Scene::normals).
struct SceneSurfaces {
  bool vertex_normals = false;     ///< some triangle has its mesh's vertex normals
  bool non_lambertian = false;     ///< some material is not Material::lambertian()
  bool cutouts = false;            ///< some material is cut out somewhere (CutoutFilter)
};

/// The variant for a scene and the settings; `specialise` false gives the
/// strategy's general variant (every light on, behind run-time checks). The
/// surfaces are the scene's whatever `specialise` says: Lambertian code
/// cannot render glass.
PathVariant choose_path_variant(SceneLighting scene, LightSampling strategy, bool aovs, bool specialise,
                                SceneSurfaces surfaces = {});

/// "mis: triangles + environment", "bsdf", ... (the report's render.path_variant).
std::string path_variant_name(const PathVariant& v);

/// Calls f.template operator()<V>() with the compiled variant equal to `v`.
/// choose_path_variant gives only compiled variants; any other is a bug
/// (KAPPA_CHECK), never a frame silently left black.
template <class F>
void with_path_variant(const PathVariant& v, F&& f) {
  const bool ran = [&]<std::size_t... I>(std::index_sequence<I...>) {
    return ((v.strategy == kPathVariants[I].strategy && v.triangle_lights == kPathVariants[I].triangle_lights &&
             v.environment == kPathVariants[I].environment && v.aovs == kPathVariants[I].aovs &&
             v.surfaces == kPathVariants[I].surfaces && v.extras == kPathVariants[I].extras &&
             (f.template operator()<kPathVariants[I]>(), true)) ||
            ...);
  }(std::make_index_sequence<kPathVariants.size()>{});
  KAPPA_CHECK(ran);
}

}  // namespace kappa
