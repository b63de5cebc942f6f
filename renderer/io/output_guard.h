// An output never replaces an input, nor another output of the same run:
// checked once the scene and every OBJ and MTL it read are known, before the
// accelerator is built.
#pragma once

#include <filesystem>
#include <vector>

namespace kappa {

/// Throws InputError (exit 2) if an output is the same file as an input or
/// as another output: by device and inode where both exist (so symlinks,
/// hard links and `..` count), else by their absolute normal paths. Empty
/// paths (outputs not asked for) are skipped.
void refuse_outputs_over_inputs(const std::vector<std::filesystem::path>& outputs,
                                const std::vector<std::filesystem::path>& inputs);

}  // namespace kappa
