// What the fuzz targets share: a scratch folder for readers that take a path,
// and the checks every target applies to what a reader accepted or refused.
// Built into two kinds of executable (tests/fuzz/CMakeLists.txt): libFuzzer's
// (clang, tools/fuzz.sh) and a replay driver that runs the saved inputs under
// tests/data/fuzz/ in the normal and sanitizer suites.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "renderer/scene/scene.h"

namespace kappa::fuzz {

/// A folder of this process's own under the temp dir, removed at exit.
const std::filesystem::path& scratch_dir();

/// Writes `size` bytes to scratch_dir()/name and returns its path.
std::filesystem::path write_scratch(const std::string& name, const std::uint8_t* data, std::size_t size);

/// Aborts unless `message` (an InputError's) starts with the path of the file
/// it refuses, "PATH[:LINE]: reason": the fuzzed file, an OBJ or MTL beside it
/// that it names, or an absolute path it names. The command line prints it as
/// one line (printable_line).
void require_refusal_names_an_input(const std::string& message);

/// Loads `file` as `kappa render` does and requires the outcome every scene
/// target requires: a scene that holds what the renderer assumes
/// (require_valid_scene), or a refusal naming a file
/// (require_refusal_names_an_input).
void load_and_check(const std::filesystem::path& file);

/// Aborts unless a scene the loader accepted holds what the renderer assumes:
/// finite vertices within the coordinate limit, a material per triangle, finite
/// albedo in [0, 1] and emission >= 0, a finite camera and environment, and a
/// film of positive size.
void require_valid_scene(const Scene& scene);

}  // namespace kappa::fuzz
