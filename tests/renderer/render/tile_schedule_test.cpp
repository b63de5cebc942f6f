// A frame split by tiles between processes (renderer/render/tile_schedule.h)
// puts together into the image one process renders: what kappa-mpi's ranks
// rely on. Here the "processes" are renders of the same frame into films of
// their own, each given every third tile.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <set>
#include <vector>

#include "renderer/render/render_helpers.h"
#include "renderer/render/tile_schedule.h"
#include "renderer/scene/scene_loader.h"
#include "test_util.h"

namespace kappa {
namespace {

/// Hands out the tiles t with t % parts == part, in order, and records what
/// the render asked of it.
class EveryKthTile final : public TileSchedule {
 public:
  EveryKthTile(std::size_t parts, std::size_t part) : m_parts(parts), m_part(part) {}
  void begin_pass(std::size_t tiles) override {
    ++begun;
    m_tiles = tiles;
    m_next = m_part;
  }
  std::optional<std::size_t> next_tile() override {
    const std::size_t tile = m_next.fetch_add(m_parts);
    if (tile >= m_tiles) return std::nullopt;
    const std::lock_guard<std::mutex> lock(m_mutex);
    handed.push_back(tile);
    return tile;
  }
  void end_pass(Film*, std::span<double>, std::span<std::uint64_t>) override { ++ended; }

  int begun = 0, ended = 0;
  std::vector<std::size_t> handed;

 private:
  std::size_t m_parts, m_part, m_tiles = 0;
  std::atomic<std::size_t> m_next{0};
  std::mutex m_mutex;
};

/// Copies tile `tile`'s pixels of every channel from `from` into `to`.
void copy_tile(const Film& from, Film& to, std::size_t tile) {
  const int tiles_x = (from.width + kTileSize - 1) / kTileSize;
  const int x0 = int(tile % std::size_t(tiles_x)) * kTileSize, y0 = int(tile / std::size_t(tiles_x)) * kTileSize;
  const auto copy = [&](const std::vector<float>& a, std::vector<float>& b, std::size_t components) {
    for (int y = y0; y < std::min(y0 + kTileSize, from.height); ++y)
      for (int x = x0; x < std::min(x0 + kTileSize, from.width); ++x)
        for (std::size_t c = 0; c < components; ++c) {
          const std::size_t i = (std::size_t(y) * std::size_t(from.width) + std::size_t(x)) * components + c;
          if (i < a.size()) b[i] = a[i];
        }
  };
  copy(from.rgb, to.rgb, 3);
  copy(from.albedo, to.albedo, 3);
  copy(from.normal, to.normal, 3);
  copy(from.depth, to.depth, 1);
}

TEST(TileSchedule, AFrameSplitByTilesIsTheWholeFrameBitwise) {
  Warnings warnings;
  Scene scene = load_scene(test::assets_dir() / "cornell-box" / "scene.json", warnings);
  scene.width = 80;  // 5 x 4 tiles, the last row and column whole
  scene.height = 56;  // and a last row of 8 pixels
  RenderSettings settings;
  settings.spp = 4;
  settings.seed = 11;
  settings.aov = AovSelection{true, true, true};
  for (const char* accel : {"naive", "grid2"}) {  // grid2: shadow rays through the per-tile occluder cache
    const Film whole = test::render_scene(scene, settings, accel);
    Film merged(scene.width, scene.height, settings.aov);
    std::multiset<std::size_t> rendered;
    constexpr std::size_t kParts = 3;
    for (std::size_t part = 0; part < kParts; ++part) {
      EveryKthTile schedule(kParts, part);
      RenderSettings split = settings;
      split.tiles = &schedule;
      const Film mine = test::render_scene(scene, split, accel);
      EXPECT_EQ(schedule.begun, 1);
      EXPECT_EQ(schedule.ended, 1);
      for (std::size_t tile : schedule.handed) {
        copy_tile(mine, merged, tile);
        rendered.insert(tile);
      }
    }
    ASSERT_EQ(rendered.size(), 20u) << accel;
    EXPECT_EQ(std::set<std::size_t>(rendered.begin(), rendered.end()).size(), 20u) << accel << ": each tile once";
    EXPECT_TRUE(test::bitwise_equal(whole.rgb, merged.rgb)) << accel;
    EXPECT_TRUE(test::bitwise_equal(whole.albedo, merged.albedo)) << accel;
    EXPECT_TRUE(test::bitwise_equal(whole.normal, merged.normal)) << accel;
    EXPECT_TRUE(test::bitwise_equal(whole.depth, merged.depth)) << accel;
  }
}

}  // namespace
}  // namespace kappa
