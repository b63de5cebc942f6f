// The pre-scan of an MTL file (a material library): its colour statements
// checked with their line numbers before tinyobjloader reads the text, which
// would otherwise turn `Ke nan` or `Kd abc` into a silent 0 and read a
// one-component colour `Kd 0.5` as (0.5, 0, 0).
#pragma once

#include <filesystem>
#include <string>

namespace kappa {

/// The text to hand tinyobjloader (and Kappa's own MTL reader): without a
/// byte-order mark and comments, every blank a space (obj_scan.h), every
/// colour statement (Ka, Kd, Ks, Ke, Tf) holding 1 or 3 finite numbers
/// within the coordinate limit, and a one-component colour written out as
/// the grey it means (g = b = r).
/// Throws InputError naming `file` and the line for anything else.
std::string scan_mtl(const std::filesystem::path& file, const std::string& text);

}  // namespace kappa
