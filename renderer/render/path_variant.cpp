#include "renderer/render/path_variant.h"

#include "core/error.h"

namespace kappa {

const char* light_sampling_name(LightSampling strategy) {
  switch (strategy) {
    case LightSampling::mis: return "mis";
    case LightSampling::nee: return "nee";
    case LightSampling::bsdf: return "bsdf";
  }
  return "?";
}

LightSampling parse_light_sampling(const std::string& name) {
  if (name == "mis") return LightSampling::mis;
  if (name == "nee") return LightSampling::nee;
  if (name == "bsdf") return LightSampling::bsdf;
  throw InputError("--light-sampling: unknown strategy '" + name + "' (expected mis, nee or bsdf)");
}

PathVariant choose_path_variant(SceneLighting scene, LightSampling strategy, bool aovs, bool specialise,
                                SceneSurfaces surfaces) {
  PathVariant v{strategy, true, true, aovs || !specialise};
  if (v.strategy == LightSampling::bsdf) v.triangle_lights = false;
  if (specialise) {
    // Punctual lights are sampled with the triangles (Lights), in the
    // variant with extras.
    if (v.strategy != LightSampling::bsdf) v.triangle_lights = scene.triangle_lights || scene.punctual_lights;
    v.environment = scene.environment;
    // Nothing light sampling could pick: BSDF sampling alone, the same estimator.
    if (!v.triangle_lights && !(v.environment && scene.environment_light)) v.strategy = LightSampling::bsdf;
  }
  v.extras = surfaces.cutouts || scene.environment_image || scene.punctual_lights;
  v.surfaces = surfaces.non_lambertian || v.extras ? Surfaces::general
               : surfaces.vertex_normals ? Surfaces::lambertian_smooth
                                         : Surfaces::lambertian;
  if (v.surfaces != Surfaces::lambertian) {
    // Compiled as the general variant only (path_variant.h).
    v.triangle_lights = v.strategy != LightSampling::bsdf;
    v.environment = true;
    v.aovs = true;
  }
  return v;
}

std::string path_variant_name(const PathVariant& v) {
  std::string name = light_sampling_name(v.strategy);
  if (v.strategy != LightSampling::bsdf) {
    name += ": ";
    name += v.triangle_lights && v.environment ? "triangles + environment" : v.triangle_lights ? "triangles" : "environment";
  } else if (v.environment) {
    name += " + environment";
  }
  if (v.surfaces == Surfaces::lambertian_smooth) name += ", shading normals";
  if (v.surfaces == Surfaces::general) name += ", materials";
  if (v.extras) name += ", extras";
  if (v.aovs) name += ", first hit";
  return name;
}

}  // namespace kappa
