// The preview: an 8-bit sRGB picture of the render beside its EXR, in any
// format OpenImageIO writes (by the file's extension: .png, .jpg, .tif), for
// a look before the EXR is opened. The tone map is Blender's "Standard" view
// transform: the linear radiance scaled by 2^exposure, clipped to [0, 1] and
// encoded with the sRGB transfer function, rounded to 8 bits.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "renderer/io/atomic_file.h"
#include "renderer/render/film.h"

namespace kappa {

/// The extensions a preview may have; throws InputError naming --preview for another.
void check_preview_name(const std::filesystem::path& file);

/// One channel of linear radiance as its 8-bit sRGB code after 2^exposure.
std::uint8_t preview_byte(float linear, float scale);

/// Encodes the film's RGB and writes it to `out`'s temporary (or device);
/// the caller commits. Throws OutputError on failure.
void write_preview(AtomicOutput& out, const Film& film, float exposure);

}  // namespace kappa
