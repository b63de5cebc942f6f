#include "renderer/scene/obj/mtl_material.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "renderer/scene/obj/mtl_texture.h"
#include "renderer/scene/obj/obj_scan.h"

namespace kappa {
namespace {

/// Why each keyword Kappa reads but does not model is ignored: the warning's words.
const std::map<std::string, std::string>& not_modelled() {
  static const std::map<std::string, std::string> reasons = {
      {"Ps", "sheen is not modelled"},
      {"Pc", "clearcoat is not modelled"},
      {"Pcr", "clearcoat is not modelled"},
      {"aniso", "anisotropic roughness is not modelled"},
      {"anisor", "anisotropic roughness is not modelled"},
      {"sharpness", "reflection-map sharpness is not modelled"},
      {"bump", "bump and normal maps are not modelled"},
      {"map_bump", "bump and normal maps are not modelled"},
      {"map_Bump", "bump and normal maps are not modelled"},
      {"norm", "bump and normal maps are not modelled"},
      {"map_norm", "bump and normal maps are not modelled"},
      {"disp", "displacement is not modelled"},
      {"map_disp", "displacement is not modelled"},
      {"decal", "decals are not modelled"},
      {"map_decal", "decals are not modelled"},
      {"map_Ka", "ambient light is not modelled"},
      {"Km", "bump multipliers are not modelled"},
  };
  return reasons;
}

/// Keywords the mapping reads (any other is unknown).
bool read_here(const std::string& k) {
  static const std::set<std::string> keys = {"Ka", "Kd", "Ks", "Ke", "Ns", "Ni", "d",  "Tr", "Tf", "Kt",
                                             "illum", "Pr", "Pm", "newmtl"};
  return keys.count(k) > 0;
}

/// The blanks split_ws splits at, and a line's carriage return.
bool blank(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f' || c == '\r'; }

/// `s` without leading and trailing blanks (comments were dropped by
/// scan_mtl, which made the text, as the OBJ scan drops them).
std::string trimmed(std::string_view s) {
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  return std::string(s);
}

class Fields {
 public:
  Fields(const MtlRecord& r, const std::filesystem::path& file, Warnings& warnings, std::set<std::string>& warned)
      : m_record(r), m_file(file), m_warnings(warnings), m_warned(warned) {
    for (const MtlStatement& s : r.statements) m_last[s.keyword] = &s;  // a later statement overrides
  }

  const MtlStatement* get(const std::string& key) const {
    const auto it = m_last.find(key);
    return it == m_last.end() ? nullptr : it->second;
  }

  double number(const MtlStatement& s, std::size_t i = 0) const {
    if (s.args.size() <= i) fail(m_file, s.line, s.keyword + " needs a number");
    double v = 0;
    switch (parse_number(s.args[i], v)) {
      case NumberStatus::invalid: fail(m_file, s.line, s.keyword + " value '" + s.args[i] + "' is not a number");
      case NumberStatus::out_of_range:
        fail(m_file, s.line, s.keyword + " value '" + s.args[i] + "' is out of the range of a double");
      case NumberStatus::ok: break;
    }
    if (!std::isfinite(v)) fail(m_file, s.line, s.keyword + " value '" + s.args[i] + "' is not finite");
    return v;
  }

  /// A scalar, clamped to [lo, hi] with a warning.
  float scalar(const MtlStatement& s, double lo, double hi, const std::string& what) const {
    if (s.args.size() != 1)
      fail(m_file, s.line, s.keyword + " needs 1 number, found " + std::to_string(s.args.size()));
    const double v = number(s);
    const double c = std::clamp(v, lo, hi);
    if (c != v) warn(s.line, s.keyword + " " + s.args[0] + " is outside " + what + ", clamped to " + format(c));
    return float(c);
  }

  /// A colour (scan_mtl made it three finite numbers), clamped to [0, hi] with a warning.
  Vec3f colour(const MtlStatement& s, double hi) const {
    if (s.args.size() != 3) fail(m_file, s.line, s.keyword + " needs 1 or 3 numbers, found " + std::to_string(s.args.size()));
    double v[3];
    bool clamped = false;
    for (std::size_t i = 0; i < 3; ++i) {
      const double x = number(s, i);
      v[i] = std::clamp(x, 0.0, hi);
      clamped |= v[i] != x;
    }
    if (clamped)
      warn(s.line, "material '" + m_record.name + "': " + s.keyword + " " + s.args[0] + " " + s.args[1] + " " +
                       s.args[2] + " is outside its valid range, clamped to " + format(v[0]) + " " + format(v[1]) +
                       " " + format(v[2]));
    return {float(v[0]), float(v[1]), float(v[2])};
  }

  void warn(std::size_t line, const std::string& message) const { m_warnings.push_back(located(m_file, line, message)); }

  /// Once per file and kind.
  void warn_once(const std::string& kind, std::size_t line, const std::string& message) const {
    if (m_warned.insert(kind).second) warn(line, message);
  }

  static std::string format(double v) {
    std::ostringstream o;
    o << v;
    return o.str();
  }

 private:
  const MtlRecord& m_record;
  const std::filesystem::path& m_file;
  Warnings& m_warnings;
  std::set<std::string>& m_warned;
  std::map<std::string, const MtlStatement*> m_last;
};

float mean(const Vec3f& c) { return (c.x + c.y + c.z) / 3.0f; }

}  // namespace

std::vector<MtlRecord> read_mtl_records(const std::filesystem::path& file, const std::string& text, Warnings& warnings) {
  std::vector<MtlRecord> records;
  std::map<std::string, std::size_t> names;  ///< each name's first definition line
  bool skipping = false;  // inside a second definition of a name
  bool warned_orphan = false;
  std::istringstream lines(text);
  std::string raw;
  for (std::size_t line_no = 1; std::getline(lines, raw); ++line_no) {
    const std::string body = trimmed(raw);
    if (body.empty()) continue;
    const auto tokens = split_ws(body);
    if (tokens.empty()) continue;  // blanks split_ws knows (vertical tab, form feed) and nothing else
    MtlStatement s{line_no, std::string(tokens[0]), {}, trimmed(std::string_view(body).substr(tokens[0].size()))};
    for (std::size_t i = 1; i < tokens.size(); ++i) s.args.emplace_back(tokens[i]);
    if (s.keyword == "newmtl") {
      // The name is the rest of the line (names with spaces exist in the wild).
      const std::string name = trimmed(std::string_view(body).substr(6));
      const auto [first, inserted] = names.emplace(name, line_no);
      skipping = !inserted;
      if (skipping) {
        // As Blender 3.4's importer: the first definition holds.
        warnings.push_back(located(file, line_no, "material '" + name + "' is defined again; its first definition, at line " +
                                                      std::to_string(first->second) + ", is used"));
        continue;
      }
      records.push_back(MtlRecord{name, line_no, {}});
      continue;
    }
    if (skipping) continue;
    if (records.empty()) {
      if (!warned_orphan)
        warnings.push_back(located(file, line_no, s.keyword + " before any newmtl is ignored"));
      warned_orphan = true;
      continue;
    }
    records.back().statements.push_back(std::move(s));
  }
  return records;
}

Material material_from_mtl(const MtlRecord& record, const std::filesystem::path& file, Warnings& warnings,
                           std::set<std::string>& warned, std::vector<TextureMap>& maps) {
  const Fields f(record, file, warnings, warned);
  Material m;
  m.name = record.name;

  // Every keyword the mapping does not read is warned about once per file.
  for (const MtlStatement& s : record.statements) {
    const auto reason = not_modelled().find(s.keyword);
    if (reason != not_modelled().end()) {
      f.warn_once(s.keyword, s.line, s.keyword + " ignored (" + reason->second + ")");
    } else if (map_slot(s.keyword)) {
      // read below
    } else if (s.keyword.rfind("map_", 0) == 0) {
      f.warn_once(s.keyword, s.line, s.keyword + " ignored (not a texture map Kappa reads)");
    } else if (!read_here(s.keyword)) {
      f.warn_once(s.keyword, s.line, s.keyword + " ignored (not an MTL keyword Kappa knows)");
    }
  }

  // The illumination model: Blender's switch (obj_import_mtl.cc).
  int illum = -1;
  if (const MtlStatement* s = f.get("illum")) {
    if (s->args.size() != 1) fail(file, s->line, "illum needs 1 number, found " + std::to_string(s->args.size()));
    const double v = f.number(*s);
    if (v != std::floor(v) || v < 0 || v > 10)
      fail(file, s->line, "illum " + s->args[0] + " is not an illumination model (an integer from 0 to 10)");
    illum = int(v);
    if (illum == 0 || illum == 10)
      f.warn_once("illum " + s->args[0], s->line,
                  "illum " + s->args[0] + " (" + (illum == 0 ? "constant colour" : "shadow matte") +
                      ") is not modelled; rendered as illum 1 (diffuse)");
  }
  const bool highlight = illum == 2;
  const bool reflection = illum == 3 || illum == 4 || illum == 5 || illum == 6 || illum == 7 || illum == 8;
  const bool transparency = illum == 4 || illum == 6 || illum == 7 || illum == 9;
  const bool glass = illum == 4 || illum == 9;

  // Base colour and emission.
  if (const MtlStatement* s = f.get("Kd")) m.albedo = f.colour(*s, 1.0);
  else m.albedo = {0.8f, 0.8f, 0.8f};  // Blender's Principled BSDF default
  if (const MtlStatement* s = f.get("Ke")) m.emission = f.colour(*s, 1e30);

  // Specular: the mean of Ks; without Ks, 1 for a highlight model, else 0.
  if (const MtlStatement* s = f.get("Ks")) {
    const Vec3f ks = f.colour(*s, 1.0);
    m.specular = mean(ks);
    if (!(ks.x == ks.y && ks.y == ks.z))
      f.warn_once("Ks colour", s->line, "Ks " + s->args[0] + " " + s->args[1] + " " + s->args[2] +
                                            ": a coloured specular is read as its mean, " + Fields::format(m.specular));
  } else {
    m.specular = highlight ? 1.0f : 0.0f;
  }

  // Roughness: Ns in [0, 1000] to 1 - sqrt(Ns / 1000); Pr, where given, wins.
  if (const MtlStatement* s = f.get("Ns")) {
    const float ns = f.scalar(*s, 0.0, 1000.0, "[0, 1000]");
    m.roughness = 1.0f - std::sqrt(ns / 1000.0f);
  } else {
    m.roughness = highlight ? 0.0f : 1.0f;
  }
  if (const MtlStatement* s = f.get("Pr")) m.roughness = f.scalar(*s, 0.0, 1.0, "[0, 1]");

  // Metallic: with a reflecting illum, the mean of Ka (1 without Ka); Pm
  // wins. The refracting models' reflection is their glass's Fresnel, so
  // they are not metals (where Blender, blending alpha, would make them one).
  const MtlStatement* ka = f.get("Ka");
  const Vec3f ambient = ka ? f.colour(*ka, 1.0) : Vec3f{0, 0, 0};
  if (reflection && !transparency) m.metallic = ka ? mean(ambient) : 1.0f;
  else if (ka && !(ambient == Vec3f{0, 0, 0}))
    f.warn_once("Ka", ka->line, "Ka ignored (ambient light is not modelled; with illum 3, 5 or 8 it is the metallic factor)");
  if (const MtlStatement* s = f.get("Pm")) m.metallic = f.scalar(*s, 0.0, 1.0, "[0, 1]");

  // Index of refraction: Ni; without it 1.5 for glass (illum 4, 9), 1 for
  // illum 6 and 7 (Blender's defaults), and 1.5 for the reflection of the
  // opaque models.
  m.ior = glass ? 1.5f : transparency ? 1.0f : 1.5f;
  if (const MtlStatement* s = f.get("Ni")) {
    if (s->args.size() != 1) fail(file, s->line, "Ni needs 1 number, found " + std::to_string(s->args.size()));
    const double ni = f.number(*s);
    if (!(ni > 0)) fail(file, s->line, "Ni " + s->args[0] + " is not an index of refraction (it must be > 0)");
    if (ni < 1) {
      f.warn(s->line, "Ni " + s->args[0] + " is below 1 (less dense than vacuum), clamped to 1");
      m.ior = 1.0f;
    } else {
      m.ior = float(ni);
    }
  }

  // Transparency: the models that refract are glass here (Blender blends alpha).
  const MtlStatement* tf = f.get("Tf") ? f.get("Tf") : f.get("Kt");
  if (transparency) {
    m.transmission = 1.0f;
    if (tf) m.transmission_tint = f.colour(*tf, 1.0);
  } else if (tf) {
    const Vec3f t = f.colour(*tf, 1.0);
    if (!(t == Vec3f{0, 0, 0}))
      f.warn_once(tf->keyword, tf->line, tf->keyword + " ignored (only illum 4, 6, 7 and 9 refract)");
  }

  // Opacity: d, or 1 - Tr.
  if (const MtlStatement* s = f.get("d")) {
    m.opacity = f.scalar(*s, 0.0, 1.0, "[0, 1]");
    if (f.get("Tr")) f.warn_once("Tr and d", f.get("Tr")->line, "Tr ignored (d is given too)");
  } else if (const MtlStatement* s = f.get("Tr")) {
    m.opacity = 1.0f - f.scalar(*s, 0.0, 1.0, "[0, 1]");
  }
  if (m.opacity < 1.0f && !f.get("map_d")) {
    // Cut-outs are binary (Material::cut_out): say what the surface becomes.
    const MtlStatement* s = f.get("d") ? f.get("d") : f.get("Tr");
    f.warn_once("opacity", s->line,
                s->keyword + " " + s->args[0] + ": partial opacity is not blended; cut-outs are binary (glTF's MASK "
                "rule), so the surface is " + (m.opacity < 0.5f ? "invisible (opacity below 0.5)" :
                                               "opaque (opacity 0.5 or more)"));
  }

  // Texture maps: the keyword that wins its slot (map_Pr over map_Ns, map_Pm
  // over map_refl over refl, as the PBR extension's scalars win theirs), its
  // last statement as for every keyword; the others are warned about.
  auto rank = [](const std::string& k) { return k == "map_Pr" || k == "map_Pm" ? 0 : k == "map_refl" ? 1 : 2; };
  std::array<const MtlStatement*, kMapSlots> chosen{};
  for (const MtlStatement& s : record.statements) {
    const auto slot = map_slot(s.keyword);
    if (!slot) continue;
    const MtlStatement*& c = chosen[std::size_t(*slot)];
    if (!c || rank(s.keyword) <= rank(c->keyword)) {
      if (c) f.warn(c->line, "material '" + record.name + "': " + c->keyword + " ignored (" + s.keyword + " drives the same parameter)");
      c = &s;
    } else {
      f.warn(s.line, "material '" + record.name + "': " + s.keyword + " ignored (" + c->keyword + " drives the same parameter)");
    }
  }
  for (std::size_t slot = 0; slot < kMapSlots; ++slot) {
    if (!chosen[slot]) continue;
    maps.push_back(texture_from_mtl(*chosen[slot], MapSlot(slot), file, warnings, warned));
    m.maps[slot] = std::int32_t(maps.size() - 1);
  }
  return m;
}

}  // namespace kappa
