// `kappa converge`: one curve per --vary value, each point the error of the
// --spp image against the reference, the self-made reference cached and
// flagged, bad input refused with exit 2.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "renderer/converge/image_error.h"
#include "renderer/io/exr_input.h"
#include "test_util.h"

namespace kappa {
namespace {

using test::run_kappa;

std::string cornell() { return (test::assets_dir() / "cornell-box" / "scene.json").string(); }

TEST(Converge, EveryVaryValueIsACurveWithAPointAtEverySpp) {
  test::TempDir tmp;
  const auto r = run_kappa({"converge", cornell(), "--width", "24", "--height", "24", "--spp", "1,2,4", "--vary",
                            "sampler=independent,sobol,stratified", "--vary", "light-sampling=nee,bsdf",
                            "--equal-time", "0.25", "--cache", (tmp / "cache").string(), "--json",
                            (tmp / "c.json").string(), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto j = nlohmann::json::parse(test::read_file(tmp / "c.json"));
  ASSERT_EQ(j.at("settings").size(), 5u);  // 3 + 2: one key at a time
  EXPECT_EQ(j.at("settings")[0].at("name"), "sampler=independent");
  EXPECT_EQ(j.at("settings")[4].at("name"), "light-sampling=bsdf");
  EXPECT_EQ(j.at("settings")[4].at("path_variant"), "bsdf");
  EXPECT_EQ(j.at("ranking").size(), 5u);
  EXPECT_EQ(j.at("equal_time_s"), 0.25);
  EXPECT_TRUE(j.at("reference").at("self_made").get<bool>());
  EXPECT_EQ(j.at("reference").at("spp"), 64);  // 16 x the largest --spp
  for (const auto& s : j.at("settings")) {
    ASSERT_EQ(s.at("points").size(), 3u) << s.at("name");
    double last_time = 0;
    for (std::size_t i = 0; i < 3; ++i) {
      const auto& p = s.at("points")[i];
      EXPECT_EQ(p.at("spp"), 1 << i);
      EXPECT_GT(p.at("relmse").get<double>(), 0);
      // One progressive render: time grows with the samples (stratified
      // renders each count on its own, so a busy machine may reorder them).
      if (s.at("name") != "sampler=stratified") {
        EXPECT_GE(p.at("time_s").get<double>(), last_time);
      }
      last_time = p.at("time_s").get<double>();
    }
  }
  // The table on stdout ranks them.
  EXPECT_NE(r.std_out.find("rank"), std::string::npos);
  EXPECT_NE(r.std_out.find("light-sampling=bsdf"), std::string::npos);
}

// A point is the error of the image `kappa render --spp N` makes, bit for
// bit: the progressive render's passes end at every N.
TEST(Converge, APointIsTheErrorOfTheSppImage) {
  test::TempDir tmp;
  const std::vector<std::string> film = {"--width", "20", "--height", "20"};
  auto args = std::vector<std::string>{"render", cornell(), "--spp", "32", "--seed", "9", "--aov", "variance",
                                       "--out", (tmp / "ref.exr").string(), "--quiet"};
  args.insert(args.end(), film.begin(), film.end());
  ASSERT_EQ(run_kappa(args).exit_code, 0);
  args = {"render", cornell(), "--spp", "3", "--sampler", "sobol", "--out", (tmp / "x.exr").string(), "--quiet"};
  args.insert(args.end(), film.begin(), film.end());
  ASSERT_EQ(run_kappa(args).exit_code, 0);
  args = {"converge", cornell(), "--spp", "1,3", "--sampler", "sobol", "--reference", (tmp / "ref.exr").string(),
          "--json", (tmp / "c.json").string(), "--quiet"};
  args.insert(args.end(), film.begin(), film.end());
  const auto r = run_kappa(args);
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto j = nlohmann::json::parse(test::read_file(tmp / "c.json"));
  const ReferenceImage ref = read_reference(tmp / "ref.exr");
  const ImageError e = image_error(read_reference(tmp / "x.exr").rgb, ref.rgb);
  const auto& p = j.at("settings")[0].at("points")[1];
  EXPECT_EQ(p.at("spp"), 3);
  EXPECT_EQ(p.at("relmse").get<double>(), e.relmse);
  EXPECT_EQ(p.at("bias").get<double>(), e.bias);
  EXPECT_FALSE(j.at("reference").at("self_made").get<bool>());
  EXPECT_EQ(j.at("reference").at("relmse_floor").get<double>(), relmse_floor(ref.variance, ref.rgb));
}

TEST(Converge, ASelfMadeReferenceIsCachedAndSaysItCannotRevealKappasBias) {
  test::TempDir tmp;
  // Curves at seeds 0 and 1: the reference takes the next seed no curve uses.
  const std::vector<std::string> args = {"converge", cornell(), "--width", "16", "--height", "16", "--spp", "1,2",
                                         "--vary", "seed=0,1", "--cache", (tmp / "cache").string(), "--json",
                                         (tmp / "c.json").string(), "--quiet"};
  const auto first = run_kappa(args);
  ASSERT_EQ(first.exit_code, 0) << first.std_err;
  EXPECT_NE(first.std_err.find("rendering the reference"), std::string::npos) << first.std_err;
  EXPECT_NE(first.std_err.find("cannot reveal Kappa's own bias"), std::string::npos) << first.std_err;
  EXPECT_EQ(nlohmann::json::parse(test::read_file(tmp / "c.json")).at("reference").at("seed"), 2);
  std::size_t cached = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(tmp / "cache")) ++cached;
  EXPECT_EQ(cached, 1u);
  const auto second = run_kappa(args);
  ASSERT_EQ(second.exit_code, 0) << second.std_err;
  EXPECT_EQ(second.std_err.find("rendering the reference"), std::string::npos) << second.std_err;
  EXPECT_NE(second.std_err.find("cannot reveal Kappa's own bias"), std::string::npos);
}

TEST(Converge, BadInputIsRefusedWithExit2) {
  test::TempDir tmp;
  const auto refused = [&](std::vector<std::string> extra, const std::string& says) {
    std::vector<std::string> args = {"converge", cornell(), "--width", "8", "--height", "8", "--spp", "1,2",
                                     "--cache", (tmp / "cache").string(), "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_kappa(args);
    EXPECT_EQ(r.exit_code, 2) << r.std_err;
    EXPECT_NE(r.std_err.find(says), std::string::npos) << r.std_err;
    EXPECT_EQ(r.err_lines().size(), 1u) << r.std_err;
  };
  refused({"--vary", "bogus=1,2"}, "--vary bogus=1");
  refused({"--vary", "max-depth=x"}, "--vary max-depth=x");
  refused({"--vary", "width=8,16"}, "the film's size is the reference's");
  refused({"--vary", "sampler"}, "is not KEY=V1,V2");
  refused({"--spp", "4,2"}, "ascending");
  refused({"--plot", (tmp / "p.txt").string()}, "must end in .png");
  // A reference of another size.
  ASSERT_EQ(run_kappa({"render", cornell(), "--width", "4", "--height", "4", "--spp", "1", "--out",
                       (tmp / "small.exr").string(), "--quiet"})
                .exit_code,
            0);
  refused({"--reference", (tmp / "small.exr").string()}, "small.exr: the reference is 4x4, the film 8x8");
  refused({"--reference", (tmp / "none.exr").string()}, "none.exr: reference image not found");
}

TEST(Converge, PlotWritesAPng) {
  if (std::system("/usr/bin/python3 -c 'import matplotlib' 2>/dev/null") != 0)
    GTEST_SKIP() << "python3-matplotlib is not installed for /usr/bin/python3 (tools/setup.sh installs it)";
  test::TempDir tmp;
  const auto r = run_kappa({"converge", cornell(), "--width", "8", "--height", "8", "--spp", "1,2", "--vary",
                            "sampler=independent,sobol", "--cache", (tmp / "cache").string(), "--plot",
                            (tmp / "p.png").string(), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const std::string png = test::read_file(tmp / "p.png");
  EXPECT_EQ(png.substr(1, 3), "PNG");
  // Only the plot (and the cache): its JSON was a temporary.
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(tmp.path())) ++files;
  EXPECT_EQ(files, 2u);
}

}  // namespace
}  // namespace kappa
