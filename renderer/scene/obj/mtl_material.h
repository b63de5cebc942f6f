// MTL materials read as the tools users export from read them: the classic
// Wavefront fields mapped onto Kappa's one material model (material.h) as
// Blender 3.4's OBJ importer maps them onto its Principled BSDF
// (obj_import_mtl.cc, set_bsdf_socket_values), the PBR extension's Pr and Pm
// taking precedence where present (Blender 3.5 onward), and the transparent
// illumination models 4, 6, 7 and 9 rendered as glass, where Blender stops
// at alpha blending. docs/scene-format.md has the table; every keyword not
// modelled is warned once per file, with its line.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "renderer/scene/material.h"
#include "renderer/scene/obj/mtl_record.h"
#include "renderer/scene/texture_map.h"

namespace kappa {

/// The materials of an MTL file's checked text (scan_mtl), in file order.
/// A name defined twice keeps its first definition (as Blender and
/// tinyobjloader do) and is warned about. Keywords before any `newmtl` are
/// warned about and ignored.
std::vector<MtlRecord> read_mtl_records(const std::filesystem::path& file, const std::string& text, Warnings& warnings);

/// The material a record describes. Throws InputError (file:line) for a value
/// Kappa refuses (a number that is not one or not finite, an illum outside
/// 0-10, an IOR <= 0); clamps others with a warning; warns once per file
/// (`warned`, the keywords already warned about in `file`) about every
/// keyword it does not model.
/// Texture maps (mtl_texture.h) are appended to `maps`, the material's
/// Material::maps indexing them.
Material material_from_mtl(const MtlRecord& record, const std::filesystem::path& file, Warnings& warnings,
                           std::set<std::string>& warned, std::vector<TextureMap>& maps);

}  // namespace kappa
