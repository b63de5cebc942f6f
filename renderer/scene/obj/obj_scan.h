// The pre-scan of an OBJ file: validates every statement with its line number
// and produces the sanitized text handed to tinyobjloader.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/task_progress.h"
#include "core/vec3.h"

namespace kappa {

struct ObjPolygon {
  std::size_t line = 0;
  std::vector<std::size_t> vertices;  ///< 0-based position indices
};

struct ObjScan {
  std::string text;                  ///< sanitized OBJ: skipped statements blanked, lines kept
  std::vector<Vec3d> positions;      ///< every `v`, validated finite and in range
  std::size_t face_count = 0;        ///< faces kept (3 or more vertices)
  std::vector<ObjPolygon> polygons;  ///< faces with more than 3 vertices
  std::vector<std::string> mtllibs;  ///< `mtllib` file names, in order
  struct MaterialUse {
    std::size_t line;
    std::string name;
  };
  std::vector<MaterialUse> material_uses;  ///< every `usemtl`
};

/// Reads and checks `file`. Throws InputError (file:line) for what Kappa
/// refuses; appends warnings for what it skips; reports its bytes done.
ObjScan scan_obj(const std::filesystem::path& file, Warnings& warnings, TaskProgress* progress = nullptr);

/// Strict number: the whole token must be a decimal floating-point literal
/// (an optional leading '+' is allowed, as OBJ writers emit it).
enum class NumberStatus { ok, invalid, out_of_range };
NumberStatus parse_number(std::string_view tok, double& out);

/// The blanks between an OBJ's or MTL's tokens: space, tab, vertical tab and
/// form feed. Every reader of the two formats (the scans, the vertex counter,
/// the text handed to tinyobjloader) uses this one definition.
constexpr bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }

/// Splits s at blanks (runs count once).
std::vector<std::string_view> split_ws(std::string_view s);

/// `line` without its comment: from a '#' that starts the line or follows a
/// blank ("usemtl red # the wall"); a '#' inside a word ("a#b") is kept.
/// Trailing blanks dropped.
std::string_view without_comment(std::string_view line);

/// Appends `line` to `out` with each blank as a space: tinyobjloader splits
/// at spaces and tabs only, and must see the tokens Kappa's scan saw.
void append_with_spaces(std::string& out, std::string_view line);

}  // namespace kappa
