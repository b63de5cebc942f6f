#include "renderer/scene/obj/mtl_texture.h"

#include <cmath>
#include <map>
#include <system_error>
#include <vector>

#include "renderer/scene/obj/obj_scan.h"

namespace kappa {
namespace {

/// Options Blender skips, with the number of words each takes.
const std::map<std::string, int>& skipped_options() {
  static const std::map<std::string, int> options = {
      {"-blendu", 1}, {"-blendv", 1}, {"-boost", 1}, {"-cc", 1}, {"-clamp", 1}, {"-imfchan", 1},
      {"-texres", 1}, {"-mm", 2},     {"-t", 3},     {"-bm", 1}, {"-type", 1},
  };
  return options;
}

bool blank(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f' || c == '\r'; }

/// The next word of `rest` from `pos` (skipping blanks); empty at the end.
std::string_view next_word(std::string_view rest, std::size_t& pos) {
  while (pos < rest.size() && blank(rest[pos])) ++pos;
  const std::size_t start = pos;
  while (pos < rest.size() && !blank(rest[pos])) ++pos;
  return rest.substr(start, pos - start);
}

bool file_exists(const std::filesystem::path& p) {
  std::error_code ec;
  return std::filesystem::exists(p, ec);
}

}  // namespace

std::optional<MapSlot> map_slot(const std::string& k) {
  if (k == "map_Kd") return MapSlot::base_color;
  if (k == "map_Ks") return MapSlot::specular;
  if (k == "map_Ns" || k == "map_Pr") return MapSlot::roughness;
  if (k == "map_Pm" || k == "map_refl" || k == "refl") return MapSlot::metallic;
  if (k == "map_Ke") return MapSlot::emission;
  if (k == "map_d") return MapSlot::opacity;
  return std::nullopt;
}

TextureMap texture_from_mtl(const MtlStatement& s, MapSlot slot, const std::filesystem::path& mtl, Warnings& warnings,
                            std::set<std::string>& warned) {
  TextureMap map;
  map.slot = slot;
  map.declared_in = mtl;
  map.line = s.line;
  map.keyword = s.keyword;
  const std::string_view rest = s.rest;
  std::size_t pos = 0;
  std::size_t name_start = rest.size();
  for (;;) {
    const std::size_t word_start = [&] {
      std::size_t p = pos;
      while (p < rest.size() && blank(rest[p])) ++p;
      return p;
    }();
    const std::string_view word = next_word(rest, pos);
    if (word.empty()) break;
    const bool placement = word == "-s" || word == "-o";
    const auto skipped = skipped_options().find(std::string(word));
    if (!placement && skipped == skipped_options().end()) {
      name_start = word_start;  // the first word that is no option begins the file name
      break;
    }
    if (placement) {
      // 1 to 3 numbers; the missing ones keep the default (0 for -o, 1 for -s).
      float v[3] = {word == "-s" ? 1.0f : 0.0f, word == "-s" ? 1.0f : 0.0f, word == "-s" ? 1.0f : 0.0f};
      int n = 0;
      while (n < 3) {
        std::size_t p = pos;
        const std::string_view number = next_word(rest, p);
        double d = 0;
        if (number.empty() || parse_number(number, d) != NumberStatus::ok) break;
        if (!std::isfinite(d) || std::abs(d) > 1e9)
          fail(mtl, s.line, s.keyword + " " + std::string(word) + " " + std::string(number) + " is not a usable number");
        v[n++] = float(d);
        pos = p;
      }
      if (n == 0) fail(mtl, s.line, s.keyword + " " + std::string(word) + " needs 1 to 3 numbers");
      if (word == "-s") map.scale = {v[0], v[1]};
      else map.offset = {v[0], v[1]};
      if (n == 3 && v[2] != (word == "-s" ? 1.0f : 0.0f) && warned.insert(std::string(word) + " w").second)
        warnings.push_back(located(mtl, s.line, s.keyword + " " + std::string(word) +
                                                    ": the third (w) component is ignored (textures are 2D)"));
      continue;
    }
    for (int k = 0; k < skipped->second; ++k) (void)next_word(rest, pos);
    if (warned.insert(std::string(word)).second)
      warnings.push_back(located(mtl, s.line, s.keyword + " option " + std::string(word) +
                                                  " ignored (Blender's importer skips it too)"));
  }
  std::string name(rest.substr(std::min(name_start, rest.size())));
  while (!name.empty() && blank(name.back())) name.pop_back();
  std::erase(name, '"');
  if (name.empty()) fail(mtl, s.line, s.keyword + " names no file");

  // Where Blender looks: beside the MTL file, as written, by its base name
  // beside the MTL file (the base name after / or \, for paths from Windows).
  const std::filesystem::path dir = mtl.parent_path();
  const std::size_t slash = name.find_last_of("/\\");
  const std::string base = slash == std::string::npos ? name : name.substr(slash + 1);
  for (const std::filesystem::path& candidate :
       {dir / name, std::filesystem::path(name), dir / base}) {
    if (file_exists(candidate)) {
      std::error_code ec;
      // A texture is read by OpenImageIO, which would wait forever on a FIFO
      // and read a device without end: regular files only.
      if (!std::filesystem::is_regular_file(candidate, ec))
        fail(mtl, s.line, s.keyword + ": texture '" + candidate.string() + "' is not a regular file");
      map.file = candidate;
      return map;
    }
  }
  fail(mtl, s.line, s.keyword + ": texture file '" + name + "' not found (looked beside the MTL file, as written, "
                    "and for '" + base + "' beside the MTL file)");
}

}  // namespace kappa
