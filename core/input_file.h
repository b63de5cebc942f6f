// Every file Kappa reads passes one check before it is opened: stat() first
// (opening a FIFO would block, and /dev/zero never ends), then only a
// regular file, after following links, of at most kMaxInputBytes, is read.
// Refusals are InputError with what the path is: "file not found", "is a
// directory", "is not a regular file (a FIFO, socket or device)", "is larger
// than ...", or the system's reason ("Permission denied").
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace kappa {

/// The largest input file Kappa reads (16 GiB): far above any scene it can
/// render in memory, low enough that a wrong path cannot fill it.
inline constexpr std::uint64_t kMaxInputBytes = std::uint64_t(16) << 30;

/// Throws InputError unless `file` is a readable regular file within the
/// limit; `kind` names what it should be ("an OBJ file", "a scene file").
void check_input_file(const std::filesystem::path& file, const char* kind);

/// The whole content of `file`, after check_input_file.
std::string read_input_file(const std::filesystem::path& file, const char* kind);

}  // namespace kappa
