// The BSDF lobes (renderer/bsdf/): every lobe's sampling against its pdf
// (chi-square), the pdf's normalisation, reciprocity, and energy (white
// furnace, a GGX albedo computed here independently).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "renderer/bsdf/chi2.h"
#include "renderer/bsdf/principled.h"
#include "renderer/render/sampling.h"

namespace kappa::bsdf {
namespace {

namespace chi2 = kappa::test::chi2;

// Samples per chi-square case and per furnace estimate: moderate, the suite
// also runs under the sanitizers.
constexpr int kChi2Samples = 200000;
constexpr int kFurnaceSamples = 100000;
constexpr double kSignificance = 0.01;

/// A lobe behind one interface: sample(wo, uc, u1, u2), pdf and eval.
struct TestLobe {
  std::string name;
  std::function<std::optional<LobeSample>(const Vec3f&, float, float, float)> sample;
  std::function<float(const Vec3f&, const Vec3f&)> pdf;
  std::function<Vec3f(const Vec3f&, const Vec3f&)> eval;
  float eta = 1;  ///< n_inside / n_outside for transmissive lobes, 1 otherwise
};

TestLobe lambertian(Vec3f R) {
  const Lambertian l{R};
  return {"Lambertian", [l](const Vec3f& wo, float, float u1, float u2) { return l.sample(wo, u1, u2); },
          [l](const Vec3f& wo, const Vec3f& wi) { return l.pdf(wo, wi); },
          [l](const Vec3f& wo, const Vec3f& wi) { return l.eval(wo, wi); }};
}

TestLobe conductor(float alpha, Vec3f f0 = {1, 1, 1}) {
  const Conductor c{Ggx(alpha), f0};
  return {"Conductor(alpha=" + std::to_string(alpha) + ")",
          [c](const Vec3f& wo, float, float u1, float u2) { return c.sample(wo, u1, u2); },
          [c](const Vec3f& wo, const Vec3f& wi) { return c.pdf(wo, wi); },
          [c](const Vec3f& wo, const Vec3f& wi) { return c.eval(wo, wi); }};
}

TestLobe dielectric(float alpha, float eta, Vec3f tint = {1, 1, 1}) {
  const Dielectric d{Ggx(alpha), eta, tint};
  return {"Dielectric(alpha=" + std::to_string(alpha) + ", eta=" + std::to_string(eta) + ")",
          [d](const Vec3f& wo, float uc, float u1, float u2) { return d.sample(wo, uc, u1, u2); },
          [d](const Vec3f& wo, const Vec3f& wi) { return d.pdf(wo, wi); },
          [d](const Vec3f& wo, const Vec3f& wi) { return d.eval(wo, wi); }, eta};
}

TestLobe principled(const std::string& name, const PrincipledParams& p) {
  const Principled m(p);
  return {"Principled(" + name + ")",
          [m](const Vec3f& wo, float uc, float u1, float u2) { return m.sample(wo, uc, u1, u2); },
          [m](const Vec3f& wo, const Vec3f& wi) { return m.pdf(wo, wi); },
          [m](const Vec3f& wo, const Vec3f& wi) { return m.eval(wo, wi); }, p.transmission > 0 ? p.ior : 1.0f};
}

/// A unit direction of cosine `cos_theta` off the axis, at an azimuth that
/// puts no lobe's peak on a bin boundary.
Vec3f direction(float cos_theta, float phi = 0.7f) {
  const float s = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}


// ---------------------------------------------------------------------------
// Chi-square

struct Chi2Case {
  std::string family;
  TestLobe lobe;
  Vec3f wo;
};

std::vector<Chi2Case> chi2_cases() {
  std::vector<Chi2Case> cases;
  for (float c : {0.9f, 0.3f}) cases.push_back({"Lambertian", lambertian({0.8f, 0.8f, 0.8f}), direction(c)});
  for (float alpha : {0.01f, 0.1f, 0.5f, 1.0f})
    for (float c : {0.9f, 0.5f, 0.1f}) cases.push_back({"Conductor", conductor(alpha), direction(c)});
  for (float alpha : {0.05f, 0.3f, 1.0f})
    for (float eta : {1.01f, 1.5f, 3.0f})
      for (float c : {0.6f, -0.6f}) {
        // Not index 1.01 at alpha 1 from outside: its refraction, 0.01 rad
        // wide, jumps to 0 at its support's edge (the horizon's microfacets
        // still have D = 1 / pi), which the bin quadrature cannot integrate
        // to the 1e-5 the no-sample cell needs. MicrofacetPdfIntegrates...
        // checks it with a quadrature centred on it.
        if (eta == 1.01f && alpha == 1.0f && c > 0.0f) continue;
        cases.push_back({"Dielectric", dielectric(alpha, eta), direction(c)});
      }
  // Grazing and near-normal glass, both sides.
  for (float c : {0.15f, -0.15f, 0.98f, -0.98f}) cases.push_back({"Dielectric", dielectric(0.3f, 1.5f), direction(c)});
  PrincipledParams metal_mix;
  metal_mix.base = {0.9f, 0.6f, 0.3f};
  metal_mix.metallic = 0.5f;
  metal_mix.roughness = 0.5f;
  metal_mix.specular = 0.5f;
  PrincipledParams glass;
  glass.transmission = 1;
  glass.roughness = 0.4f;
  PrincipledParams coat;  // diffuse base under a rough dielectric coat
  coat.base = {0.2f, 0.5f, 0.8f};
  coat.roughness = 0.3f;
  coat.specular = 1.0f;
  PrincipledParams smooth_coat = coat;  // the coat a delta lobe
  smooth_coat.roughness = 0;
  PrincipledParams everything;  // every lobe at once
  everything.base = {0.7f, 0.7f, 0.5f};
  everything.roughness = 0.6f;
  everything.metallic = 0.3f;
  everything.transmission = 0.5f;
  everything.ior = 1.33f;
  for (float c : {0.8f, 0.2f}) {
    cases.push_back({"Principled", principled("metallic 0.5", metal_mix), direction(c)});
    cases.push_back({"Principled", principled("diffuse+coat", coat), direction(c)});
    cases.push_back({"Principled", principled("diffuse+smooth coat", smooth_coat), direction(c)});
  }
  for (float c : {0.7f, -0.7f}) {
    cases.push_back({"Principled", principled("glass", glass), direction(c)});
    cases.push_back({"Principled", principled("everything", everything), direction(c)});
  }
  return cases;
}

/// Where a lobe's density may peak too narrowly for the first quadrature
/// nodes: the mirror direction, and for glass the refracted one about the
/// normal and -wo (refraction through the microfacet of normal wo, where
/// an index near 1 focuses every microfacet's refraction).
std::vector<Vec3f> peaks(const Vec3f& wo, float eta) {
  std::vector<Vec3f> p{Vec3f{-wo.x, -wo.y, wo.z}};
  float etap = 1;
  Vec3f wt;
  if (eta != 1.0f) {
    if (refract(wo, Vec3f{0, 0, 1}, eta, etap, wt)) p.push_back(wt);
    p.push_back(-wo);
  }
  return p;
}

struct Chi2Outcome {
  chi2::Result result;
  double continuous_fraction = 0;  ///< samples that gave a non-delta direction
  double pdf_integral = 0;
  int mismatches = 0;  ///< samples whose f or pdf disagree with eval and pdf
};

Chi2Outcome run_chi2(const Chi2Case& c, std::uint64_t seed) {
  const chi2::Grid grid{12, 24};
  const int cells = grid.bins();
  std::vector<double> observed(cells + 1, 0.0);  // the last: no continuous direction
  Rng rng(seed, 0, 0);
  Chi2Outcome out;
  for (int i = 0; i < kChi2Samples; ++i) {
    const float uc = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    const std::optional<LobeSample> s = c.lobe.sample(c.wo, uc, u1, u2);
    if (!s || s->delta || !(s->pdf > 0.0f)) {
      observed[cells] += 1;
      continue;
    }
    observed[grid.bin(s->wi)] += 1;
    const float p = c.lobe.pdf(c.wo, s->wi);
    const Vec3f f = c.lobe.eval(c.wo, s->wi);
    if (std::abs(p - s->pdf) > 1e-3f * p || std::abs(f.x - s->f.x) > 1e-3f * f.x + 1e-6f) ++out.mismatches;
  }
  std::vector<double> expected = chi2::integrate_bins([&](const Vec3f& wi) { return c.lobe.pdf(c.wo, wi); }, grid,
                                                      peaks(c.wo, c.lobe.eta));
  double integral = 0;
  for (double& e : expected) {
    integral += e;
    e *= kChi2Samples;
  }
  expected.push_back(std::max(0.0, 1.0 - integral) * kChi2Samples);
  out.pdf_integral = integral;
  out.continuous_fraction = 1.0 - observed[cells] / kChi2Samples;
  out.result = chi2::pearson(observed, expected, kChi2Samples);
  return out;
}

void chi2_family(const std::string& family) {
  const std::vector<Chi2Case> cases = chi2_cases();
  const double level = chi2::sidak(kSignificance, int(cases.size()));
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Chi2Case& c = cases[i];
    if (c.family != family) continue;
    const Chi2Outcome o = run_chi2(c, 1000 + i);
    std::printf("  chi2 %-52s wo.z=%5.2f  chi2=%9.2f dof=%3d p=%.4f  integral=%.5f sampled=%.5f\n",
                c.lobe.name.c_str(), c.wo.z, o.result.chi2, o.result.dof, o.result.pvalue, o.pdf_integral,
                o.continuous_fraction);
    const std::string what = c.lobe.name + " at wo.z = " + std::to_string(c.wo.z);
    EXPECT_GT(o.result.pvalue, level) << what << ": chi2 " << o.result.chi2 << ", dof " << o.result.dof << " "
                                      << o.result.message;
    EXPECT_EQ(o.mismatches, 0) << what << ": sample()'s f or pdf disagree with eval() or pdf()";
  }
}

TEST(BsdfChi2, Lambertian) { chi2_family("Lambertian"); }
TEST(BsdfChi2, Conductor) { chi2_family("Conductor"); }
TEST(BsdfChi2, RoughDielectric) { chi2_family("Dielectric"); }
TEST(BsdfChi2, Principled) { chi2_family("Principled"); }

TEST(BsdfChi2, PValueMatchesKnownQuantiles) {
  // chi2 quantiles: P(X >= x) for x the 0.95 / 0.01 critical values.
  EXPECT_NEAR(chi2::chi2_pvalue(3.841459, 1), 0.05, 1e-6);
  EXPECT_NEAR(chi2::chi2_pvalue(18.307038, 10), 0.05, 1e-6);
  EXPECT_NEAR(chi2::chi2_pvalue(135.806723, 100), 0.01, 1e-6);
  EXPECT_NEAR(chi2::chi2_pvalue(2.0, 2), std::exp(-1.0), 1e-12);  // dof 2: exp(-x/2)
  EXPECT_NEAR(chi2::chi2_pvalue(1e-3, 300), 1.0, 1e-12);
  EXPECT_LT(chi2::chi2_pvalue(1000.0, 300), 1e-40);
}

// ---------------------------------------------------------------------------
// Normalisation

/// The pdf over the whole sphere, by the same bin quadrature as chi-square.
double pdf_integral(const TestLobe& lobe, const Vec3f& wo) {
  double sum = 0;
  for (double e : chi2::integrate_bins([&](const Vec3f& wi) { return lobe.pdf(wo, wi); }, chi2::Grid{8, 16},
                                       peaks(wo, lobe.eta)))
    sum += e;
  return sum;
}

/// The fraction of samples that give a direction of positive pdf.
double success_fraction(const TestLobe& lobe, const Vec3f& wo, int n, std::uint64_t seed) {
  Rng rng(seed, 1, 2);
  int ok = 0;
  for (int i = 0; i < n; ++i) {
    const float uc = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    const std::optional<LobeSample> s = lobe.sample(wo, uc, u1, u2);
    ok += s && !s->delta && s->pdf > 0.0f;
  }
  return double(ok) / n;
}

TEST(BsdfPdf, LambertianIntegratesToOne) {
  for (float c : {1.0f, 0.7f, 0.2f, -0.5f}) EXPECT_NEAR(pdf_integral(lambertian({1, 1, 1}), direction(c)), 1.0, 1e-3);
}

TEST(BsdfPdf, MicrofacetPdfIntegratesToTheSampledFraction) {
  // Conductor sampling loses the normals whose reflection goes below the
  // horizon (and the dielectric's total internal reflections through a
  // back-facing refraction...), so the pdf integrates to that success
  // fraction, at most 1.
  const int n = 100000;
  std::vector<std::pair<TestLobe, Vec3f>> cases;
  for (float alpha : {0.05f, 0.5f, 1.0f})
    for (float c : {0.95f, 0.4f, 0.1f}) cases.push_back({conductor(alpha), direction(c)});
  for (float alpha : {0.1f, 0.6f})
    for (float c : {0.8f, 0.2f, -0.8f, -0.2f}) cases.push_back({dielectric(alpha, 1.5f), direction(c)});
  for (const auto& [lobe, wo] : cases) {
    const double integral = pdf_integral(lobe, wo);
    const double frac = success_fraction(lobe, wo, n, 7);
    const double se = std::sqrt(std::max(frac * (1 - frac), 1e-4) / n);
    EXPECT_LE(integral, 1.0 + 1e-3) << lobe.name << " wo.z " << wo.z;
    EXPECT_NEAR(integral, frac, 4 * se + 1e-3) << lobe.name << " wo.z " << wo.z;
  }
}

/// The pdf over the sphere in polar coordinates about `centre`, the radius
/// log-spaced: for a lobe far narrower than any bin.
double pdf_integral_about(const TestLobe& lobe, const Vec3f& wo, const Vec3f& centre) {
  const Frame frame(centre);
  const int n_rho = 3000, n_psi = 400;
  const double u0 = std::log(1e-7), u1 = std::log(chi2::kPi), du = (u1 - u0) / n_rho;
  double sum = 0;
  for (int i = 0; i < n_rho; ++i) {
    const double rho = std::exp(u0 + (i + 0.5) * du);
    double ring = 0;
    for (int j = 0; j < n_psi; ++j) ring += lobe.pdf(wo, normalize(frame.to_world(chi2::spherical(rho, 2 * chi2::kPi * (j + 0.5) / n_psi))));
    sum += ring * (2 * chi2::kPi / n_psi) * std::sin(rho) * rho * du;
  }
  return sum;
}

TEST(BsdfPdf, NearUnityIndexRefractionIntegratesToTheSampledFraction) {
  // Index 1.01 at alpha 1: every microfacet refracts within ~0.01 rad of -wo.
  const TestLobe lobe = dielectric(1.0f, 1.01f);
  const int n = 200000;
  for (float c : {0.6f, -0.6f}) {
    const Vec3f wo = direction(c);
    const double integral = pdf_integral_about(lobe, wo, -wo);
    const double frac = success_fraction(lobe, wo, n, 11);
    EXPECT_NEAR(integral, frac, 4 * std::sqrt(std::max(frac * (1 - frac), 1e-4) / n) + 1e-4) << "wo.z " << c;
  }
}

// ---------------------------------------------------------------------------
// Reciprocity

/// Uniform direction on the sphere away from the horizon (|z| >= 0.05).
Vec3f random_direction(Rng& rng) {
  for (;;) {
    const float z = 2 * rng.uniform() - 1, phi = 2 * std::numbers::pi_v<float> * rng.uniform();
    if (std::abs(z) < 0.05f) continue;
    const float r = std::sqrt(1 - z * z);
    return {r * std::cos(phi), r * std::sin(phi), z};
  }
}

/// Equal to `rel`, or to 1e-4 absolute: near total internal reflection 1 - F
/// and so a refraction's f is tiny and all rounding.
bool near(const Vec3f& a, const Vec3f& b, float rel) {
  const auto close = [rel](float x, float y) { return std::abs(x - y) <= rel * std::max(std::abs(x), std::abs(y)) + 1e-4f; };
  return close(a.x, b.x) && close(a.y, b.y) && close(a.z, b.z);
}

TEST(BsdfReciprocity, ReflectionIsSymmetric) {
  std::vector<TestLobe> lobes{lambertian({0.3f, 0.6f, 0.9f})};
  for (float alpha : {0.05f, 0.3f, 1.0f}) {
    lobes.push_back(conductor(alpha, {0.9f, 0.5f, 0.2f}));
    lobes.push_back(dielectric(alpha, 1.5f));  // its reflection, on either side
  }
  PrincipledParams p;
  p.base = {0.8f, 0.4f, 0.2f};
  p.metallic = 0.4f;
  p.roughness = 0.5f;
  lobes.push_back(principled("metallic 0.4", p));
  Rng rng(3, 4, 5);
  for (const TestLobe& lobe : lobes) {
    int checked = 0;
    for (int i = 0; i < 20000; ++i) {
      const Vec3f wo = random_direction(rng), wi = random_direction(rng);
      if (!same_hemisphere(wo, wi)) continue;
      const Vec3f a = lobe.eval(wo, wi), b = lobe.eval(wi, wo);
      ++checked;
      ASSERT_TRUE(near(a, b, 1e-3f)) << lobe.name << ": f(wo, wi) = " << a.x << ", f(wi, wo) = " << b.x;
    }
    EXPECT_GT(checked, 5000) << lobe.name;
  }
}

TEST(BsdfReciprocity, RefractionObeysGeneralisedReciprocity) {
  // Walter's BTDF for radiance, with wo in a medium of index n_o and wi in
  // one of index n_i, is S(wo, wi) * n_o^2 with S symmetric (D, G, 1 - F,
  // |wi.wm| |wo.wm| / (cos cos (n_i wi.wm + n_o wo.wm)^2) all are): it is
  // pbrt's n_i^2 S scaled by 1/etap^2, etap = n_i / n_o. Hence Veach's
  // generalised reciprocity (1997, eq. 5.14) f(wo, wi) / n_o^2 = f(wi, wo) / n_i^2,
  // i.e. f(wi, wo) = etap^2 f(wo, wi): f is not symmetric, f * etap^2 /
  // n_i^2 (the unscaled BTDF over the index squared of its incident side) is.
  // Dropping the 1/etap^2 (or applying it both ways) breaks this.
  Rng rng(6, 7, 8);
  std::vector<TestLobe> lobes;
  for (float alpha : {0.05f, 0.3f, 1.0f})
    for (float eta : {1.33f, 1.5f, 2.4f}) lobes.push_back(dielectric(alpha, eta, {0.9f, 0.7f, 0.5f}));
  PrincipledParams glass;
  glass.transmission = 0.8f;
  glass.roughness = 0.5f;
  glass.ior = 1.5f;
  lobes.push_back(principled("glass 0.8", glass));
  for (const TestLobe& lobe : lobes) {
    int checked = 0;
    for (int i = 0; i < 20000; ++i) {
      const Vec3f wo = random_direction(rng), wi = random_direction(rng);
      if (same_hemisphere(wo, wi)) continue;
      const Vec3f a = lobe.eval(wo, wi), b = lobe.eval(wi, wo);
      const float n_o = wo.z > 0 ? 1.0f : lobe.eta, n_i = wi.z > 0 ? 1.0f : lobe.eta;
      const float etap = n_i / n_o;
      if (max_component(a) > 0.0f) ++checked;
      ASSERT_TRUE(near(a * (etap * etap), b, 2e-3f))
          << lobe.name << ": f(wo, wi) etap^2 = " << a.x * etap * etap << ", f(wi, wo) = " << b.x << ", wo.z " << wo.z;
    }
    EXPECT_GT(checked, 1000) << lobe.name;
  }
}

// ---------------------------------------------------------------------------
// Energy

struct Furnace {
  double mean = 0, se = 0;
};

/// The directional albedo int f |cos| dwi by the lobe's own sampling; each
/// refracted sample's weight times etap^2 if `unscale` (radiance's 1/eta'^2
/// compression undone: the energy that crosses).
Furnace furnace(const TestLobe& lobe, const Vec3f& wo, int n, std::uint64_t seed, bool unscale) {
  Rng rng(seed, 3, 3);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const float uc = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    const std::optional<LobeSample> s = lobe.sample(wo, uc, u1, u2);
    double w = 0;
    if (s && s->pdf > 0.0f) w = s->f.x * std::abs(s->wi.z) / s->pdf * (unscale ? s->etap * s->etap : 1.0f);
    sum += w;
    sum2 += w * w;
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

/// The same by uniform sampling of the sphere, stratified in (z, phi):
/// reads eval only.
Furnace furnace_uniform(const TestLobe& lobe, const Vec3f& wo, int n_z, int n_phi, std::uint64_t seed) {
  Rng rng(seed, 4, 4);
  double sum = 0;
  for (int i = 0; i < n_z; ++i)
    for (int j = 0; j < n_phi; ++j) {
      const float z = -1 + 2 * (i + rng.uniform()) / n_z, phi = 2 * std::numbers::pi_v<float> * (j + rng.uniform()) / n_phi;
      const float r = std::sqrt(std::max(0.0f, 1 - z * z));
      sum += lobe.eval(wo, Vec3f{r * std::cos(phi), r * std::sin(phi), z}).x * std::abs(z);
    }
  return {sum * 4 * chi2::kPi / (double(n_z) * n_phi), 0.0};
}

TEST(BsdfEnergy, WhiteLambertianReflectsEverything) {
  const TestLobe lobe = lambertian({1, 1, 1});
  for (float c : {0.95f, 0.5f, 0.1f, -0.5f}) {
    const Furnace is = furnace(lobe, direction(c), kFurnaceSamples, 1, false);
    EXPECT_NEAR(is.mean, 1.0, 1e-5) << c;
    EXPECT_NEAR(furnace_uniform(lobe, direction(c), 250, 400, 2).mean, 1.0, 1e-3) << c;
  }
}

TEST(BsdfEnergy, NoLobeCreatesEnergy) {
  std::vector<TestLobe> lobes;
  for (float alpha : {0.01f, 0.1f, 0.5f, 1.0f}) lobes.push_back(conductor(alpha));
  for (float alpha : {0.05f, 0.3f, 1.0f})
    for (float eta : {1.01f, 1.5f, 3.0f}) lobes.push_back(dielectric(alpha, eta));
  PrincipledParams metal_mix;
  metal_mix.base = {1, 1, 1};
  metal_mix.metallic = 0.5f;
  metal_mix.roughness = 0.5f;
  lobes.push_back(principled("white, metallic 0.5", metal_mix));
  PrincipledParams glass;
  glass.transmission = 1;
  glass.roughness = 0.4f;
  lobes.push_back(principled("glass", glass));
  for (const TestLobe& lobe : lobes)
    for (float c : {0.9f, 0.5f, 0.1f, -0.9f, -0.5f, -0.1f}) {
      if (c < 0.0f && lobe.eta == 1.0f) continue;  // opaque: one-sided
      const Furnace f = furnace(lobe, direction(c), kFurnaceSamples / 4, 5, true);
      std::printf("  furnace %-46s wo.z=%5.2f  %.4f +- %.4f\n", lobe.name.c_str(), c, f.mean, f.se);
      EXPECT_LE(f.mean - 3 * f.se, 1.0) << lobe.name << " wo.z " << c;
    }
}

TEST(BsdfEnergy, NearlySmoothGlassLosesAlmostNothing) {
  // Single scattering loses little at alpha 0.05: reflection plus
  // refraction (etap^2 undone) stays within 1% of 1.
  for (float eta : {1.5f, 3.0f})
    for (float c : {0.9f, 0.5f, -0.9f, -0.5f}) {
      const Furnace f = furnace(dielectric(0.05f, eta), direction(c), kFurnaceSamples, 9, true);
      EXPECT_NEAR(f.mean, 1.0, 0.01) << "eta " << eta << " wo.z " << c;
    }
}

/// Unpolarised Fresnel reflectance from Snell's law, written here anew:
/// light in a medium of index n1 meeting one of index n2 at cos_1.
double fresnel_reference(double cos_1, double n1, double n2) {
  const double sin_2 = n1 / n2 * std::sqrt(std::max(0.0, 1 - cos_1 * cos_1));
  if (sin_2 >= 1) return 1;
  const double cos_2 = std::sqrt(1 - sin_2 * sin_2);
  const double rs = (n1 * cos_1 - n2 * cos_2) / (n1 * cos_1 + n2 * cos_2);
  const double rp = (n2 * cos_1 - n1 * cos_2) / (n2 * cos_1 + n1 * cos_2);
  return 0.5 * (rs * rs + rp * rp);
}

TEST(BsdfEnergy, SmoothGlassSplitsEnergyByFresnel) {
  // R + T = 1 exactly: every delta sample's weight f |cos| / pdf is 1 once
  // its 1/etap^2 is undone, reflection is chosen with probability R, and
  // the refracted direction obeys Snell's law.
  const int n = 50000;
  for (float eta : {1.33f, 1.5f, 2.4f})
    for (float c : {1.0f, 0.7f, 0.2f, -1.0f, -0.9f, -0.7f, -0.3f}) {
      const Dielectric d{Ggx(0), eta, {1, 1, 1}};
      const Vec3f wo = direction(c);
      const double n1 = c > 0 ? 1.0 : eta, n2 = c > 0 ? eta : 1.0;
      const double R = fresnel_reference(std::abs(c), n1, n2);
      EXPECT_NEAR(fresnel_dielectric(c, eta), R, 1e-5) << eta << " " << c;
      Rng rng(12, 13, 14);
      int reflected = 0;
      for (int i = 0; i < n; ++i) {
        const std::optional<LobeSample> s = d.sample(wo, rng.uniform(), rng.uniform(), rng.uniform());
        ASSERT_TRUE(s.has_value());
        ASSERT_TRUE(s->delta);
        const double w = s->f.x * std::abs(s->wi.z) / s->pdf * s->etap * s->etap;
        ASSERT_NEAR(w, 1.0, 1e-5);
        if (same_hemisphere(wo, s->wi)) {
          ++reflected;
          ASSERT_NEAR(s->wi.x, -wo.x, 1e-6f);
          ASSERT_NEAR(s->wi.z, wo.z, 1e-6f);
        } else {
          // Snell: n1 sin_1 = n2 sin_2, the azimuth turned by pi, etap = n2 / n1.
          const double sin_2 = std::sqrt(std::max(0.0f, 1 - s->wi.z * s->wi.z));
          ASSERT_NEAR(n2 * sin_2, n1 * std::sqrt(1 - c * c), 1e-5);
          ASSERT_NEAR(s->etap, n2 / n1, 1e-6);
          ASSERT_LE(s->wi.x * wo.x + s->wi.y * wo.y, 1e-7f);
        }
      }
      const double se = std::sqrt(std::max(R * (1 - R), 1e-6) / n);
      EXPECT_NEAR(double(reflected) / n, R, 4 * se + 1e-6) << "eta " << eta << " wo.z " << c;
    }
}

/// GGX's directional albedo with F = 1: int D(wm) G2(wo, wi) / (4 cos_o) dwi
/// over the upper hemisphere, D and the height-correlated Smith G written
/// here anew, by a dense midpoint rule in double.
double ggx_albedo_reference(double alpha, double cos_o) {
  const double a2 = alpha * alpha;
  const auto lambda = [a2](double c) { return 0.5 * (std::sqrt(1 + a2 * (1 - c * c) / (c * c)) - 1); };
  const auto D = [a2](double c) {
    const double k = (a2 - 1) * c * c + 1;
    return a2 / (chi2::kPi * k * k);
  };
  const double so = std::sqrt(1 - cos_o * cos_o);
  const int n_theta = 600, n_phi = 600;  // phi over [0, pi], symmetric
  double sum = 0;
  for (int i = 0; i < n_theta; ++i) {
    const double t = 0.5 * chi2::kPi * (i + 0.5) / n_theta, ci = std::cos(t), si = std::sin(t);
    for (int j = 0; j < n_phi; ++j) {
      const double phi = chi2::kPi * (j + 0.5) / n_phi;
      const double hx = so + si * std::cos(phi), hy = si * std::sin(phi), hz = cos_o + ci;
      const double ch = hz / std::sqrt(hx * hx + hy * hy + hz * hz);
      sum += D(ch) / (1 + lambda(cos_o) + lambda(ci)) / (4 * cos_o) * si;
    }
  }
  return 2 * sum * (0.5 * chi2::kPi / n_theta) * (chi2::kPi / n_phi);
}

TEST(BsdfEnergy, GgxAlbedoMatchesAnIndependentQuadrature) {
  const TestLobe lobe = conductor(1.0f, {1, 1, 1});
  for (float c : {0.9f, 0.5f, 0.2f}) {
    const double reference = ggx_albedo_reference(1.0, c);
    const Furnace f = furnace(lobe, direction(c, 0.0f), kFurnaceSamples, 21, false);
    std::printf("  GGX alpha 1 albedo at cos %.1f: reference %.5f, sampled %.5f +- %.5f\n", c, reference, f.mean, f.se);
    EXPECT_NEAR(f.mean, reference, 0.01 * reference) << c;
    EXPECT_NEAR(f.mean, reference, 4 * f.se + 1e-3) << c;
    // eval itself, integrated deterministically (stratified, one sample per stratum).
    EXPECT_NEAR(furnace_uniform(lobe, direction(c, 0.0f), 300, 600, 22).mean, reference, 0.002 * reference) << c;
  }
}

}  // namespace
}  // namespace kappa::bsdf
