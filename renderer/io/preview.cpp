#include "renderer/io/preview.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/input_error.h"
#include "core/srgb.h"
#include "renderer/image/image_library.h"

namespace kappa {
namespace {

std::string lower_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

void check_preview_name(const std::filesystem::path& file) {
  const std::string ext = lower_extension(file);
  if (ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".tif" && ext != ".tiff")
    throw InputError("--preview: '" + file.string() + "' must end in .png, .jpg, .jpeg, .tif or .tiff");
}

std::uint8_t preview_byte(float linear, float scale) { return linear_to_srgb_byte(linear, scale); }

void write_preview(AtomicOutput& out, const Film& film, float exposure) {
  const float scale = std::exp2(exposure);
  std::vector<std::uint8_t> pixels(film.rgb.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = preview_byte(film.rgb[i], scale);
  std::vector<std::uint8_t> bytes;
  try {
    bytes = image_library().encode_8bit(lower_extension(out.target()), film.width, film.height, 3, pixels);
  } catch (const std::runtime_error& e) {
    throw OutputError("--preview " + out.target().string() + ": " + e.what());
  }
  write_temporary(out, std::string(bytes.begin(), bytes.end()));
}

}  // namespace kappa
