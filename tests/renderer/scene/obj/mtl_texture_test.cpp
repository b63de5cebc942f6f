// MTL texture statements read as Blender 3.4's importer reads them
// (renderer/scene/obj/mtl_texture.h): -s and -o placing the coordinates,
// other options skipped and warned about, the file name the rest of the
// line, looked for beside the MTL file, as written, then by base name; the
// keyword that wins a slot; a file found nowhere or not a regular file refused.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>

#include "core/input_error.h"
#include "renderer/scene/obj/mtl_material.h"
#include "renderer/scene/obj/mtl_texture.h"
#include "test_util.h"

namespace kappa {
namespace {

class MtlTexture : public ::testing::Test {
 protected:
  void SetUp() override {
    m_dir = std::filesystem::temp_directory_path() / ("kappa_mtl_tex_" + std::to_string(::getpid()));
    std::filesystem::create_directories(m_dir / "sub dir");
    test::write_file(m_dir / "a.png", "x");
    test::write_file(m_dir / "sub dir" / "b c.png", "x");
  }
  void TearDown() override { std::filesystem::remove_all(m_dir); }

  /// The material of `text` (one newmtl), its maps and warnings.
  Material read(const std::string& text, std::vector<TextureMap>& maps, Warnings& w) {
    const std::vector<MtlRecord> records = read_mtl_records(m_dir / "m.mtl", text, w);
    std::set<std::string> warned;
    return material_from_mtl(records.at(0), m_dir / "m.mtl", w, warned, maps);
  }

  std::filesystem::path m_dir;
};

bool any_contains(const Warnings& w, const std::string& s) {
  for (const std::string& x : w)
    if (x.find(s) != std::string::npos) return true;
  return false;
}

TEST_F(MtlTexture, ScaleAndOffsetPlaceTheCoordinatesAndOtherOptionsAreWarnedAboutOnce) {
  std::vector<TextureMap> maps;
  Warnings w;
  const Material m = read("newmtl a\nmap_Kd -s 2 3 1 -o 0.5 -clamp on -bm 0.3 -mm 0 1 a.png\n", maps, w);
  ASSERT_EQ(maps.size(), 1u);
  EXPECT_EQ(m.maps[std::size_t(MapSlot::base_color)], 0);
  EXPECT_TRUE(m.textured());
  EXPECT_FALSE(m.lambertian());
  const TextureMap& t = maps[0];
  EXPECT_EQ(t.file, m_dir / "a.png");
  EXPECT_EQ(t.line, 2u);
  EXPECT_EQ(t.scale, (Vec2f{2, 3}));
  EXPECT_EQ(t.offset, (Vec2f{0.5f, 0}));  // one number: v keeps 0
  EXPECT_TRUE(any_contains(w, "m.mtl:2: map_Kd option -clamp ignored"));
  EXPECT_TRUE(any_contains(w, "map_Kd option -bm ignored"));
  EXPECT_TRUE(any_contains(w, "map_Kd option -mm ignored"));
}

TEST_F(MtlTexture, TheFileNameIsTheRestOfTheLineWithItsSpacesAndWithoutQuotes) {
  std::vector<TextureMap> maps;
  Warnings w;
  read("newmtl a\nmap_Kd \"sub dir/b c.png\"\n", maps, w);
  ASSERT_EQ(maps.size(), 1u);
  EXPECT_EQ(maps[0].file, m_dir / "sub dir/b c.png");
}

TEST_F(MtlTexture, AWindowsPathIsFoundByItsBaseNameBesideTheMtl) {
  std::vector<TextureMap> maps;
  Warnings w;
  read("newmtl a\nmap_d C:\\textures\\a.png\n", maps, w);
  ASSERT_EQ(maps.size(), 1u);
  EXPECT_EQ(maps[0].file, m_dir / "a.png");
  EXPECT_EQ(maps[0].slot, MapSlot::opacity);
}

TEST_F(MtlTexture, EachKeywordDrivesItsSlotAndThePbrMapsWin) {
  std::vector<TextureMap> maps;
  Warnings w;
  const Material m =
      read("newmtl a\nmap_Ns a.png\nmap_Pr a.png\nrefl a.png\nmap_Pm a.png\nmap_Ks a.png\nmap_d a.png\n", maps, w);
  ASSERT_EQ(maps.size(), 4u);
  EXPECT_EQ(maps[std::size_t(m.maps[std::size_t(MapSlot::roughness)])].keyword, "map_Pr");
  EXPECT_EQ(maps[std::size_t(m.maps[std::size_t(MapSlot::metallic)])].keyword, "map_Pm");
  EXPECT_EQ(maps[std::size_t(m.maps[std::size_t(MapSlot::specular)])].keyword, "map_Ks");
  EXPECT_TRUE(m.cut_out());
  EXPECT_TRUE(any_contains(w, "m.mtl:2: material 'a': map_Ns ignored (map_Pr drives the same parameter)"));
  EXPECT_TRUE(any_contains(w, "m.mtl:4: material 'a': refl ignored (map_Pm drives the same parameter)"));
}

TEST_F(MtlTexture, AFileFoundNowhereOrNotARegularFileIsRefusedWithItsLine) {
  std::vector<TextureMap> maps;
  Warnings w;
  try {
    read("newmtl a\nKd 1 1 1\nmap_Kd nope.png\n", maps, w);
    FAIL() << "no refusal";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("m.mtl:3: map_Kd: texture file 'nope.png' not found"), std::string::npos)
        << e.what();
  }
  ASSERT_EQ(::mkfifo((m_dir / "fifo.png").c_str(), 0600), 0);
  EXPECT_THROW(read("newmtl a\nmap_Kd fifo.png\n", maps, w), InputError);
  EXPECT_THROW(read("newmtl a\nmap_Kd sub dir\n", maps, w), InputError);
  EXPECT_THROW(read("newmtl a\nmap_Kd -s 2\n", maps, w), InputError);  // options and no file
  EXPECT_THROW(read("newmtl a\nmap_Kd -s x a.png\n", maps, w), InputError);
}

}  // namespace
}  // namespace kappa
