// An MTL file's statements as read, before any is mapped: what the material
// mapping (mtl_material.h) and the texture statements (mtl_texture.h) read.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace kappa {

/// One statement of a material: its keyword and the words after it.
struct MtlStatement {
  std::size_t line = 0;
  std::string keyword;
  std::vector<std::string> args;
  std::string rest;  ///< the line after the keyword, blanks at the ends trimmed (a file name may hold spaces)
};

/// A `newmtl` block: the material's name and its statements, in order.
struct MtlRecord {
  std::string name;
  std::size_t line = 0;
  std::vector<MtlStatement> statements;
};

}  // namespace kappa
