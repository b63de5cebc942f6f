// The cost model's constants: the fit recovers known values, files round-trip,
// and a calibrated render reports predicted beside measured time.
#include "stats/calibration.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <nlohmann/json.hpp>

#include "core/input_error.h"
#include "test_util.h"

namespace kappa {
namespace {

/// A measurement made up from known eq 10 constants (ns): T0 + cells Ts + tests Th.
TimedLoad eq10_load(double T0, double Ts, double Th, double cells, double tests, double rays = 1000) {
  TimedLoad m;
  m.load.rays = rays;
  m.load.cells = cells * rays;
  m.load.tests = tests * rays;
  m.seconds = (T0 + Ts * cells + Th * tests) * 1e-9 * rays;
  return m;
}

TEST(Calibration, FitRecoversExactConstants) {
  // seconds = T0 + cells Ts + tests Th with T0 = 30 ns, Ts = 5 ns, Th = 8 ns.
  std::vector<TimedLoad> samples;
  for (double cells : {2.0, 10.0, 40.0})
    for (double tests : {1.0, 7.0, 90.0}) samples.push_back(eq10_load(30, 5, 8, cells, tests));
  TimeModel m = eq10_model();
  fit(m, samples);
  EXPECT_NEAR(m.ns[0], 30.0, 1e-6);
  EXPECT_NEAR(m.ns[1], 5.0, 1e-6);
  EXPECT_NEAR(m.ns[2], 8.0, 1e-6);
  EXPECT_NEAR(m.rms_relative_error, 0.0, 1e-9);
  EXPECT_NEAR(m.seconds(eq10_load(0, 0, 0, 3, 4, 10).load), 10 * (30 + 15 + 32) * 1e-9, 1e-15);
}

/// Loads that vary every feature of the extended model apart (each class,
/// cells, occupied share, tests, skips, hits, the working set and the share
/// of it the lists hold), each twice: with few and with many cold steps when
/// `cold`, without and with sub-grids entered when `descents`; timed by
/// `truth`.
std::vector<TimedLoad> varied_loads(const TimeModel& truth, bool cold, bool descents) {
  const double cache = truth.cache_bytes;
  std::vector<TimedLoad> samples;
  int i = 0;
  for (std::size_t c = 0; c < kRenderClasses; ++c)
    for (double cells : {3.0, 30.0})
      for (double occupied_share : {0.1, 0.6})
        for (double tests : {2.0, 50.0})
          for (double working_set : {0.5 * cache, 4 * cache, 300 * cache})
            for (const bool more : {false, true}) {
              TimedLoad m;
              m.load = QueryLoad{RenderClass(c), 1000, 1000 * cells, 1000 * cells * occupied_share, 1000 * tests,
                                 1000.0 * (1 + (i % 5)), 1000.0 * (i % 3) / 2.0, working_set};
              m.load.list_bytes = working_set * (i % 3 ? 0.3 : 0.8);  // the steps' and the tests' bytes vary apart
              if (cold) {
                const double cold_share = more ? 0.7 : 0.05;
                m.load.cold_cells = 1000 * cells * cold_share;
                m.load.cold_tests = 1000 * tests * cold_share * (i % 2 ? 0.5 : 1.0);
              }
              if (descents) m.load.descents = more ? 1000 * 2.5 * (i % 4 ? 1.0 : 0.4) : 0.0;
              m.seconds = truth.seconds(m.load);
              samples.push_back(m);
              ++i;
            }
  return samples;
}

TEST(Calibration, TheExtendedModelRecoversEveryTermOfAClosedFormCase) {
  // Times made from known values of all its terms, over loads that vary each
  // feature apart: the fit returns each term, and the prediction of a load
  // it never saw is exact.
  const double cache = 1 << 20;
  TimeModel truth = extended_model(cache);
  for (std::size_t k = 0; k < truth.ns.size(); ++k) truth.ns[k] = 1.0 + double((7 * k) % 11);
  const std::vector<TimedLoad> samples = varied_loads(truth, false, false);
  TimeModel m = extended_model(cache);
  fit(m, samples);
  for (std::size_t k = 0; k < m.ns.size(); ++k) EXPECT_NEAR(m.ns[k], truth.ns[k], 1e-6) << m.terms[k];
  EXPECT_NEAR(m.rms_relative_error, 0.0, 1e-9);
  QueryLoad unseen{kBounce2, 500, 500 * 12.0, 500 * 2.0, 500 * 9.0, 500 * 2.0, 400, 40 * cache};
  unseen.list_bytes = 25 * cache;
  EXPECT_NEAR(m.seconds(unseen) / truth.seconds(unseen), 1.0, 1e-9);
}

TEST(Calibration, AStepIsJudgedByTheCellsBytesAndATestByTheListsAndTriangles) {
  // 4 MiB of which the lists and triangles are 0.5 MiB (the teapot in the
  // stadium's case: a large grid of mostly empty cells, triangles that fit
  // in L2): a step's share beyond the cache is 1 - 1 / 3.5, a test's 0; with
  // lists of 3.5 MiB, a step's is 0 (0.5 MiB of cells) and a test's 1 - 1 / 3.5.
  const double cache = 1 << 20;
  const TimeModel m = extended_model(cache);
  const auto index = [&](const std::string& term) {
    return std::size_t(std::find(m.terms.begin(), m.terms.end(), term) - m.terms.begin());
  };
  QueryLoad load{kShadow, 10, 10 * 8.0, 10 * 2.0, 10 * 30.0, 0, 5, 4 * cache};
  load.list_bytes = 0.5 * cache;
  std::vector<double> f = m.features_per_ray(load);
  EXPECT_NEAR(f[index("Ts_miss_shadow")], 8.0 * (1 - 1 / 3.5), 1e-12);
  EXPECT_EQ(f[index("Th_miss_shadow")], 0.0);
  EXPECT_EQ(f[index("Ts_miss_camera")], 0.0);  // another class's terms stay 0
  load.list_bytes = 3.5 * cache;
  f = m.features_per_ray(load);
  EXPECT_EQ(f[index("Ts_miss_shadow")], 0.0);
  EXPECT_NEAR(f[index("Th_miss_shadow")], 30.0 * (1 - 1 / 3.5), 1e-12);
  EXPECT_EQ(m.terms.back(), "Th_miss_bounce3+");  // the grid's model has no term per descent
}

TEST(Calibration, Grid2sModelRecoversItsCostPerSubGridEntered) {
  // grid2's models end with T_descend, a cost per sub-grid entered: fitted
  // to times that include one, both forms return it and every other term.
  const double cache = 1 << 20;
  for (const bool coherent : {false, true}) {
    TimeModel truth = coherent ? coherent_model(cache, true) : extended_model(cache, true);
    ASSERT_EQ(truth.terms.back(), "T_descend");
    ASSERT_EQ(truth.terms.size(), (coherent ? coherent_model(cache) : extended_model(cache)).terms.size() + 1);
    for (std::size_t k = 0; k < truth.ns.size(); ++k) truth.ns[k] = 1.0 + double((3 * k) % 7);
    truth.ns.back() = 47.5;
    std::vector<TimedLoad> samples = varied_loads(truth, coherent, true);
    TimeModel fitted = coherent ? *fit_coherent(samples, true) : extended_model(cache, true);
    if (!coherent) fit(fitted, samples);
    for (std::size_t k = 0; k < truth.ns.size(); ++k) EXPECT_NEAR(fitted.ns[k], truth.ns[k], 1e-6) << fitted.terms[k];
    // The same loads timed without the descents' cost: the term comes out 0.
    for (TimedLoad& m : samples) m.seconds -= 47.5e-9 * m.load.descents;
    fit(fitted, samples);
    EXPECT_NEAR(fitted.ns.back(), 0.0, 1e-6);
  }
}

TEST(Calibration, TheCoherentModelRecoversItsColdStepTerm) {
  // Times with a known cost per cold step on top of the extended terms: the
  // coherent fit returns it; measurements without a cold step have no
  // coherent model.
  const double cache = 1 << 20;
  TimeModel truth = coherent_model(cache);
  for (std::size_t k = 0; k < truth.ns.size(); ++k) truth.ns[k] = 1.0 + double((5 * k) % 7);
  truth.ns.back() = 3.5;  // Ts_cold
  std::vector<TimedLoad> samples = varied_loads(truth, true, false);
  const std::optional<TimeModel> fitted = fit_coherent(samples);
  ASSERT_TRUE(fitted);
  EXPECT_EQ(fitted->terms.back(), "Ts_cold");
  for (std::size_t k = 0; k < truth.ns.size(); ++k) EXPECT_NEAR(fitted->ns[k], truth.ns[k], 1e-6) << fitted->terms[k];
  for (TimedLoad& m : samples) m.load.cold_cells = m.load.cold_tests = 0;
  EXPECT_FALSE(fit_coherent(samples));
}

TEST(Calibration, TheCoherentModelChargesColdStepsNotColdTests) {
  // One term beyond the extended model's, per cold step: the calibration
  // frames did not determine a cost per test in a cold cell (time_model.h),
  // so the tests made in cold cells are counted and reported but no
  // prediction depends on them.
  const double cache = 1 << 20;
  const TimeModel m = coherent_model(cache);
  ASSERT_EQ(m.terms.size(), extended_model(cache).terms.size() + 1);
  EXPECT_EQ(m.terms.back(), "Ts_cold");
  QueryLoad load{kBounce1, 10, 10 * 8.0, 10 * 2.0, 10 * 30.0, 0, 5, 4 * cache};
  load.list_bytes = cache;
  load.cold_cells = 10 * 3.0;
  load.cold_tests = 10 * 12.0;
  const std::vector<double> f = m.features_per_ray(load);
  EXPECT_NEAR(f.back(), 3.0, 1e-12);
  load.cold_tests = 0;
  EXPECT_EQ(m.features_per_ray(load), f);
}

TEST(Calibration, NoConstantComesOutNegative) {
  // Times that the free fit explains with T0 = -20 ns: the fit holds T0 at 0
  // and is then the best non-negative one, which for T0 = 0 is the least
  // squares fit of (cells, tests) alone; checked against that fit computed
  // here in closed form.
  std::vector<TimedLoad> samples;
  for (double cells : {10.0, 40.0, 80.0})
    for (double tests : {5.0, 20.0, 60.0}) samples.push_back(eq10_load(-20, 5, 8, cells, tests));
  TimeModel m = eq10_model();
  fit(m, samples);
  EXPECT_EQ(m.ns[0], 0.0);
  EXPECT_GT(m.ns[1], 0.0);
  EXPECT_GT(m.ns[2], 0.0);
  // Normal equations of the two-term fit of the relative error.
  double a11 = 0, a12 = 0, a22 = 0, b1 = 0, b2 = 0;
  for (const TimedLoad& s : samples) {
    const double t = s.seconds / s.load.rays * 1e9;
    const double c = s.load.cells / s.load.rays / t, h = s.load.tests / s.load.rays / t;
    a11 += c * c, a12 += c * h, a22 += h * h, b1 += c, b2 += h;
  }
  const double det = a11 * a22 - a12 * a12;
  EXPECT_NEAR(m.ns[1], (b1 * a22 - b2 * a12) / det, 1e-6);
  EXPECT_NEAR(m.ns[2], (a11 * b2 - a12 * b1) / det, 1e-6);
}

TEST(Calibration, TooFewOrDegenerateMeasurementsAreRefused) {
  TimeModel m = eq10_model();
  const std::vector<TimedLoad> two = {eq10_load(10, 1, 1, 1, 1), eq10_load(10, 1, 1, 2, 2)};
  EXPECT_THROW(fit(m, two), std::runtime_error);
  // Tests always equal to cells: Ts and Th cannot be told apart.
  const std::vector<TimedLoad> collinear = {eq10_load(10, 1, 1, 1, 1), eq10_load(10, 1, 1, 2, 2),
                                            eq10_load(10, 1, 1, 3, 3)};
  EXPECT_THROW(fit(m, collinear), std::runtime_error);
}

TEST(Calibration, FileRoundTripAndErrors) {
  test::TempDir tmp;
  EXPECT_FALSE(load_calibration(tmp / "none.json"));
  Calibration c;
  c.eq10.ns = {1.5, 2.5, 3.5};
  for (std::size_t k = 0; k < c.extended.ns.size(); ++k) c.extended.ns[k] = 0.5 + double(k);
  c.build.ns = {14, 130, 1.5};
  c.build.threads = 2;
  c.naive.ns = {40, 2.5, 0.75};
  c.samples = 9;
  test::write_file(tmp / "c.json", to_json(c).dump());
  const auto back = load_calibration(tmp / "c.json");
  ASSERT_TRUE(back);
  EXPECT_EQ(back->eq10.ns, c.eq10.ns);
  EXPECT_EQ(back->extended.ns, c.extended.ns);
  EXPECT_EQ(back->extended.cache_bytes, c.extended.cache_bytes);
  EXPECT_EQ(back->build.ns, c.build.ns);
  EXPECT_EQ(back->build.threads, 2);
  EXPECT_EQ(back->naive.ns, c.naive.ns);
  EXPECT_EQ(back->source, (tmp / "c.json").string());
  EXPECT_EQ(back->probe_s, 0.0);  // none measured: none written, none read
  c.probe_s = 0.0042;
  test::write_file(tmp / "probe.json", to_json(c).dump());
  EXPECT_EQ(load_calibration(tmp / "probe.json")->probe_s, 0.0042);
  // The coherent models: optional (none written, none read), each read back
  // when present, a malformed one refused.
  EXPECT_FALSE(load_calibration(tmp / "c.json")->coherent);
  Calibration coherent = c;
  coherent.coherent = coherent_model(1 << 20);
  for (std::size_t k = 0; k < coherent.coherent->ns.size(); ++k) coherent.coherent->ns[k] = 0.25 + double(k);
  test::write_file(tmp / "coherent.json", to_json(coherent).dump());
  const auto coherent_back = load_calibration(tmp / "coherent.json");
  ASSERT_TRUE(coherent_back && coherent_back->coherent);
  EXPECT_EQ(coherent_back->coherent->ns, coherent.coherent->ns);
  EXPECT_EQ(coherent_back->coherent->form, ModelForm::coherent);
  EXPECT_FALSE(coherent_back->grid2_coherent);  // written as null
  coherent.grid2_coherent = coherent_model(1 << 20, /*nested=*/true);
  for (std::size_t k = 0; k < coherent.grid2_coherent->ns.size(); ++k) coherent.grid2_coherent->ns[k] = 0.5 + double(k);
  coherent.grid2_coherent->ns.back() = 42;  // T_descend: grid2's alone
  test::write_file(tmp / "coherent2.json", to_json(coherent).dump());
  const auto grid2_back = load_calibration(tmp / "coherent2.json");
  ASSERT_TRUE(grid2_back && grid2_back->grid2_coherent);
  EXPECT_EQ(grid2_back->grid2_coherent->ns, coherent.grid2_coherent->ns);
  EXPECT_EQ(grid2_back->grid2_coherent->terms.back(), "T_descend");
  EXPECT_EQ(grid2_back->grid2.traversal.terms.back(), "T_descend");
  nlohmann::json null_coherent = to_json(coherent);
  null_coherent["coherent"] = nullptr;  // as absent
  test::write_file(tmp / "null_coherent.json", null_coherent.dump());
  EXPECT_FALSE(load_calibration(tmp / "null_coherent.json")->coherent);
  for (const char* bad : {R"({"grid": {"constants": {"Ts_ns": 1}}, "grid2": null})", R"("fast")", R"({"grid2": null})"}) {
    nlohmann::json j = to_json(coherent);
    j["coherent"] = nlohmann::json::parse(bad);
    test::write_file(tmp / "bad_coherent.json", j.dump());
    EXPECT_THROW(load_calibration(tmp / "bad_coherent.json"), InputError) << bad;
  }
  for (const char* bad : {"\"fast\"", "-1", "0"}) {
    nlohmann::json j = to_json(c);
    j["machine_probe_s"] = nlohmann::json::parse(bad);
    test::write_file(tmp / "bad_probe.json", j.dump());
    EXPECT_THROW(load_calibration(tmp / "bad_probe.json"), InputError) << bad;
  }
  // A file of this format without the build model's constants (format 3's content) is not a calibration.
  nlohmann::json no_build = to_json(c);
  no_build.erase("build");
  test::write_file(tmp / "no_build.json", no_build.dump());
  EXPECT_THROW(load_calibration(tmp / "no_build.json"), InputError);
  // Nor one without the naive model's (format 4's content).
  nlohmann::json no_naive = to_json(c);
  no_naive.erase("naive");
  test::write_file(tmp / "no_naive.json", no_naive.dump());
  EXPECT_THROW(load_calibration(tmp / "no_naive.json"), InputError);
  test::write_file(tmp / "bad.json", "{\"format\": " + std::to_string(kCalibrationFormat) +
                                          ", \"eq10\": {\"constants\": {\"T0_ns\": \"fast\"}}}");
  EXPECT_THROW(load_calibration(tmp / "bad.json"), InputError);
  // A file of the first format (eq 10 alone, Th per reference): refused with
  // a word to calibrate again, not read as something it is not.
  test::write_file(tmp / "old.json", R"({"T0_ns": 20, "Ts_ns": 3, "Th_ns": 7})");
  // What a render asks of the file beside the binary before it reads it: an
  // older one is set aside with a warning, not a refusal.
  EXPECT_FALSE(calibration_of_another_format(tmp / "c.json"));
  EXPECT_TRUE(calibration_of_another_format(tmp / "old.json"));
  EXPECT_FALSE(calibration_of_another_format(tmp / "none.json"));
  EXPECT_FALSE(calibration_of_another_format(tmp / "bad.json"));  // malformed: refused by load_calibration
  test::write_file(tmp / "format2.json", R"({"format": 2, "eq10": {}})");
  EXPECT_TRUE(calibration_of_another_format(tmp / "format2.json"));
  try {
    load_calibration(tmp / "old.json");
    ADD_FAILURE() << "an old calibration was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("run kappa calibrate again"), std::string::npos) << e.what();
  }
}

TEST(Calibration, CalibrateThenRenderReportsTheCost) {
  test::TempDir tmp;
  const auto cal = (tmp / "cal.json").string();
  const auto c = test::run_kappa(
      {"calibrate", "--spp", "2", "--size", "32", "--repeat", "1", "--density", "2,16", "--out", cal});
  ASSERT_EQ(c.exit_code, 0) << c.std_err;
  const auto calibration = nlohmann::json::parse(test::read_file(cal));
  EXPECT_EQ(calibration.at("format"), kCalibrationFormat);
  // Frames of the two asset scenes at 2 densities and the generated soups
  // and meshes at theirs, one measurement per ray class with at least 256 rays.
  const auto& measurements = calibration.at("measurements");
  EXPECT_EQ(calibration.at("samples"), measurements.size());
  EXPECT_GE(measurements.size(), 20u);
  for (const char* scene : {"cornell-box", "scene_lowres", "soup3000", "soup30000", "soup300000"}) {
    bool found = false;
    for (const auto& m : measurements) found = found || m.at("label").get<std::string>().rfind(scene, 0) == 0;
    EXPECT_TRUE(found) << scene;
  }
  // grid2's own frames beside them: one per scene and density, at grid2 top
  // densities 1/64 of the grid's; its traversal and build constants fitted.
  const auto& grid2 = calibration.at("grid2_measurements");
  EXPECT_GE(grid2.size(), 20u);
  for (const auto& m : grid2) EXPECT_NE(m.at("label").get<std::string>().find(" grid2 top "), std::string::npos) << m;
  const auto at_top_quarter = [](const nlohmann::json& m) {
    return m.at("label").get<std::string>().find("grid2 top 0.25") != std::string::npos;
  };
  EXPECT_TRUE(std::any_of(grid2.begin(), grid2.end(), at_top_quarter)) << "density 16: grid2's top density 0.25";
  EXPECT_GT(calibration.at("grid2").at("build").at("constants").at("per_triangle_ns").get<double>() +
                calibration.at("grid2").at("build").at("constants").at("per_reference_ns").get<double>(),
            0.0);
  EXPECT_EQ(calibration.at("grid2_builds").size(), calibration.at("builds").size());
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  const auto r = test::run_kappa({"render", scene, "--accel", "grid", "--spp", "2", "--width", "32", "--height", "32", "--out",
                                  (tmp / "x.exr").string(), "--report", (tmp / "x.json").string(), "--calibration", cal});
  // grid2's render is predicted by its own constants.
  const auto r2 = test::run_kappa({"render", scene, "--spp", "2", "--width", "32", "--height", "32", "--accel", "grid2",
                                   "--out", (tmp / "g.exr").string(), "--report", (tmp / "g.json").string(),
                                   "--calibration", cal});
  ASSERT_EQ(r2.exit_code, 0) << r2.std_err;
  const auto g = nlohmann::json::parse(test::read_file(tmp / "g.json")).at("cost");
  EXPECT_GT(g.at("extended").at("predicted_s").get<double>(), 0.0);
  EXPECT_EQ(g.at("extended").at("constants"), calibration.at("grid2").at("traversal").at("constants"));
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto report = nlohmann::json::parse(test::read_file(tmp / "x.json"));
  const auto& cost = report.at("cost");
  EXPECT_GT(cost.at("measured_s").get<double>(), 0.0);
  for (const char* model : {"eq10", "extended", "coherent"}) {
    EXPECT_GT(cost.at(model).at("predicted_s").get<double>(), 0.0) << model;
    EXPECT_TRUE(cost.at(model).at("relative_error").is_number()) << model;
  }
  // The coherent model is the calibration's, over the frame's cold steps.
  EXPECT_EQ(cost.at("coherent").at("constants"), calibration.at("coherent").at("grid").at("constants"));
  EXPECT_GT(cost.at("per_class").at("camera").at("cold_cells_per_ray").get<double>(), 0.0);
  EXPECT_NE(r.std_err.find("s predicted"), std::string::npos) << r.std_err;
  // A named calibration that does not exist is an error, not a silent null.
  const auto missing = test::run_kappa({"render", scene, "--spp", "1", "--out", (tmp / "y.exr").string(),
                                        "--calibration", (tmp / "nope.json").string()});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(tmp / "y.exr"));
}

}  // namespace
}  // namespace kappa

namespace kappa {
namespace {

TEST(Calibration, NonPositiveTimesAreRefused) {
  std::vector<TimedLoad> samples = {eq10_load(10, 1, 1, 1, 1), eq10_load(10, 1, 1, 2, 5), eq10_load(10, 1, 1, 3, 2)};
  samples[1].seconds = 0;
  EXPECT_THROW(fit_calibration(samples), std::runtime_error);
}

TEST(Calibration, ABadCalibrationFileIsRefusedBeforeRendering) {
  test::TempDir tmp;
  test::write_file(tmp / "bad.json", "{\"format\": 3, \"eq10\": null}");
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  const auto r = test::run_kappa({"render", scene, "--spp", "1000", "--out", (tmp / "x.exr").string(), "--calibration",
                                  (tmp / "bad.json").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err_lines().size(), 1u) << r.std_err;
  EXPECT_FALSE(std::filesystem::exists(tmp / "x.exr"));
}

TEST(Calibration, RefusedPerCellStatisticsSkipTheCellMapButKeepTheImage) {
  test::TempDir tmp;
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  const auto r = test::run_kappa({"render", scene, "--accel", "grid", "--spp", "1", "--width", "8", "--height", "8", "--out",
                                  (tmp / "x.exr").string(), "--cell-map", (tmp / "m.exr").string(), "--grid-max-bytes",
                                  "9000", "--quiet"});
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  EXPECT_TRUE(std::filesystem::exists(tmp / "x.exr"));
  EXPECT_FALSE(std::filesystem::exists(tmp / "m.exr"));
  EXPECT_NE(r.std_err.find("--cell-map skipped"), std::string::npos) << r.std_err;
}

}  // namespace
}  // namespace kappa
