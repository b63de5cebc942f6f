// EXR output read back with OpenEXR: pixels, channels and metadata.
#include "renderer/io/exr_output.h"

#include <gtest/gtest.h>

#include "image_files.h"
#include "renderer/io/atomic_file.h"
#include "test_util.h"

namespace kappa {
namespace {

Film sample_film() {
  Film film(5, 3, AovSelection{true, true, true});
  for (std::size_t i = 0; i < film.rgb.size(); ++i) film.rgb[i] = float(i) * 0.25f + 1e-7f;
  for (std::size_t i = 0; i < film.albedo.size(); ++i) film.albedo[i] = float(i) / 64.0f;
  for (std::size_t i = 0; i < film.normal.size(); ++i) film.normal[i] = -float(i) / 32.0f;
  for (std::size_t i = 0; i < film.depth.size(); ++i) film.depth[i] = i == 4 ? INFINITY : float(i) * 3.5f;
  return film;
}

TEST(Exr, RoundTripKeepsPixelsChannelsAndMetadata) {
  test::TempDir dir;
  const Film film = sample_film();
  const auto path = dir / "round.exr";
  write_exr(path, film, {{"kappa:scene", std::string("x/scene.json")}, {"kappa:spp", 17}, {"kappa:render_time_s", 1.5f}});

  const test::ExrFile in = test::read_exr_file(path);
  EXPECT_EQ(in.width, 5);
  EXPECT_EQ(in.height, 3);
  const std::vector<std::string> expected = {"R", "G", "B", "albedo.R", "albedo.G", "albedo.B",
                                             "normal.X", "normal.Y", "normal.Z", "depth.Z"};
  ASSERT_EQ(in.channels.size(), expected.size());
  // EXR stores channels sorted by name; look each one up.
  const std::vector<float>& pixels = in.pixels;
  auto channel = [&](const std::string& name) {
    const int c = in.channel(name);
    if (c < 0) ADD_FAILURE() << "missing channel " << name;
    return std::max(c, 0);
  };
  const std::size_t nc = in.channels.size();
  for (std::size_t i = 0; i < film.pixels(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const std::size_t k = 3 * i + std::size_t(c);
      EXPECT_EQ(pixels[i * nc + std::size_t(channel(expected[std::size_t(c)]))], film.rgb[k]);
      EXPECT_EQ(pixels[i * nc + std::size_t(channel(expected[3 + std::size_t(c)]))], film.albedo[k]);
      EXPECT_EQ(pixels[i * nc + std::size_t(channel(expected[6 + std::size_t(c)]))], film.normal[k]);
    }
    EXPECT_EQ(pixels[i * nc + std::size_t(channel("depth.Z"))], film.depth[i]);
  }
  EXPECT_EQ(in.string_attribute("kappa:scene"), "x/scene.json");
  EXPECT_EQ(in.int_attribute("kappa:spp"), 17);
  EXPECT_EQ(in.float_attribute("kappa:render_time_s"), 1.5f);
  // The time of writing, as OpenEXR's standard capDate ("YYYY:MM:DD hh:mm:ss").
  EXPECT_EQ(in.string_attribute("capDate").size(), 19u) << in.string_attribute("capDate");
}

TEST(Exr, VarianceAndSppChannelsFollowTheOthers) {
  test::TempDir dir;
  AovSelection aov;
  aov.depth = aov.cost = aov.variance = aov.spp = true;
  Film film(2, 2, aov);
  for (std::size_t i = 0; i < film.pixels(); ++i) {
    film.depth[i] = 1.5f + float(i);
    film.cost_cells[i] = 10.0f + float(i);
    film.cost_tests[i] = 20.0f + float(i);
    film.spp[i] = 16.0f * float(i + 1);
    for (int c = 0; c < 3; ++c) film.variance[3 * i + std::size_t(c)] = 0.125f * float(c + 1) + float(i);
  }
  EXPECT_EQ(exr_channel_names(film),
            (std::vector<std::string>{"R", "G", "B", "depth.Z", "cost.cells", "cost.tests", "variance.R", "variance.G",
                                      "variance.B", "spp"}));
  const auto path = dir / "aov.exr";
  write_exr(path, film, {});
  const test::ExrFile in = test::read_exr_file(path);
  ASSERT_EQ(in.channels.size(), 10u);
  const auto value = [&](std::size_t pixel, const std::string& name) {
    const int c = in.channel(name);
    if (c >= 0) return in.pixels[pixel * in.channels.size() + std::size_t(c)];
    ADD_FAILURE() << "missing channel " << name;
    return -1.0f;
  };
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(value(i, "spp"), film.spp[i]);
    EXPECT_EQ(value(i, "variance.G"), film.variance[3 * i + 1]);
    EXPECT_EQ(value(i, "depth.Z"), film.depth[i]);
    EXPECT_EQ(value(i, "cost.tests"), film.cost_tests[i]);
  }
}

TEST(Exr, AtomicOutputLeavesNothingBehindWithoutCommit) {
  test::TempDir dir;
  const auto target = dir / "out.exr";
  test::write_file(target, "previous contents");
  {
    AtomicOutput output(target);
    write_exr(output.temp_path(), sample_film(), {});
    // No commit: as if the render failed after writing.
  }
  EXPECT_EQ(test::read_file(target), "previous contents");
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, 1u);
}

TEST(Exr, AtomicOutputCommitReplacesTheTarget) {
  test::TempDir dir;
  const auto target = dir / "out.exr";
  test::write_file(target, "previous contents");
  {
    AtomicOutput output(target);
    write_exr(output.temp_path(), sample_film(), {});
    output.commit();
  }
  EXPECT_EQ(test::read_exr_file(target).width, 5);
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, 1u);
}

}  // namespace
}  // namespace kappa
