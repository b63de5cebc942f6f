// An MTL texture statement (map_Kd [options] file) read as Blender 3.4's OBJ
// importer reads it (obj_import_file_reader.cc, parse_texture_option;
// obj_import_mtl.cc, add_image_textures and load_texture_image): the
// options -s and -o place the coordinates (uv * s + o, its Mapping node);
// every other option is skipped with its arguments and warned about once
// per file; the file name is the rest of the line, quotes removed; it is
// looked for beside the MTL file, then as written, then by its base name
// beside the MTL file.
#pragma once

#include <filesystem>
#include <optional>
#include <set>
#include <string>

#include "core/error.h"
#include "renderer/scene/obj/mtl_record.h"
#include "renderer/scene/texture_map.h"

namespace kappa {

/// The slot a map keyword drives, or none for a keyword that is not a map
/// Kappa reads (map_Ns and map_Pr both drive roughness; map_refl, refl and
/// map_Pm metallic, as in Blender).
std::optional<MapSlot> map_slot(const std::string& keyword);

/// The map `s` names in `mtl`. Throws InputError (file:line) for a statement
/// without a file name, a malformed -s or -o, or a file found nowhere.
TextureMap texture_from_mtl(const MtlStatement& s, MapSlot slot, const std::filesystem::path& mtl, Warnings& warnings,
                            std::set<std::string>& warned);

}  // namespace kappa
