// The RGB pixels of an EXR a command wrote, for tests that compare images
// bitwise (grid choice, accelerator choice).
#pragma once

#include <filesystem>
#include <vector>

#include "image_files.h"

namespace kappa::test {

inline std::vector<float> exr_rgb(const std::filesystem::path& exr) {
  const ExrFile image = read_exr_file(exr);
  const std::vector<float> r = image.values("R"), g = image.values("G"), b = image.values("B");
  std::vector<float> v;
  for (std::size_t i = 0; i < r.size() && i < g.size() && i < b.size(); ++i) v.insert(v.end(), {r[i], g[i], b[i]});
  return v;
}

}  // namespace kappa::test
