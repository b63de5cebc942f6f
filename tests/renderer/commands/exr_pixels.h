// The RGB pixels of an EXR a command wrote, for tests that compare images
// bitwise (grid choice, accelerator choice).
#pragma once

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <vector>

namespace kappa::test {

inline std::vector<float> exr_rgb(const std::filesystem::path& exr) {
  auto in = OIIO::ImageInput::open(exr.string());
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return {};
  std::vector<float> v(std::size_t(in->spec().width * in->spec().height * 3));
  in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, v.data());
  return v;
}

}  // namespace kappa::test
