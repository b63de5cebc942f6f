// A progressive render's checkpoint (--checkpoint-every, --resume): the
// passes it has completed (renderer/render/frame_progress.h), saved beside
// its image as IMAGE.checkpoint, atomically, and read back to go on from.
// A header line, a JSON line (the Kappa that wrote it, the settings that
// decide the image, the passes and counts, the arrays' sizes), the arrays
// as they are in memory, and the FNV-1a 64 of all that before them: a
// checkpoint cut short or changed is refused, as is one of another Kappa,
// another scene or other settings, each with a line that says which.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "renderer/render/frame_progress.h"

namespace kappa {

/// The checkpoint of a render's image `image`.
std::filesystem::path checkpoint_path(const std::filesystem::path& image);

/// `progress` as a checkpoint's bytes, for a render of `settings` (the
/// settings that decide its image and counts, render_record.h's).
std::string encode_checkpoint(const nlohmann::ordered_json& settings, const FrameProgress& progress);

/// A checkpoint's bytes read back, for a render of `settings` whose frame
/// has `pixels` pixels, with AOV sums if `aovs`: throws InputError naming
/// `file` when they are not a checkpoint of Kappa's, are damaged, come from
/// another version of Kappa, or from other settings (the first that differs).
FrameProgress decode_checkpoint(const std::string& bytes, const std::string& file,
                                const nlohmann::ordered_json& settings, std::size_t pixels, bool aovs);

}  // namespace kappa
