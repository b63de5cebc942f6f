// Every file Kappa reads passes one check before it is opened: stat() first
// (opening a FIFO would block, and /dev/zero never ends), then only a
// regular file, after following links, within the input limit (a quarter of
// the memory this process may use: reading and parsing a file needs a few
// times its size) is read. Refusals are InputError with what the path is:
// "file not found", "is a directory", "is not a regular file (a FIFO, socket
// or device)", "is larger than ...", or the system's reason ("Permission
// denied").
//
// A file is read once, in blocks, and judged while it is read: text stops at
// its first byte that no text holds (a control character), JSON too at its
// first byte that is not UTF-8, and a line longer than kMaxTextLineBytes, so
// a 2 GiB file of NULs costs one block. Its bytes are hashed as they come,
// and the file, its size and hash recorded: the report's provenance is the
// bytes that were parsed, and no input is opened again after loading.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace kappa {

/// The largest input file Kappa reads: a quarter of usable_memory_bytes().
std::uint64_t max_input_bytes();

/// A line of a text input longer than this (64 MiB) is refused: no OBJ,
/// MTL or scene file holds one (an OBJ face of 300,000 vertices is 3 MiB).
inline constexpr std::uint64_t kMaxTextLineBytes = std::uint64_t(64) << 20;

/// What a file's content must be.
enum class InputContent {
  binary,  ///< anything (images, binary glTF, buffers)
  text,    ///< no control characters but tab, line breaks, \v and \f; any 8-bit encoding
  utf8,    ///< text, and valid UTF-8 (JSON)
};

/// Throws InputError unless `file` is a readable regular file within the
/// limit; `kind` names what it should be ("an OBJ file", "a scene file").
void check_input_file(const std::filesystem::path& file, const char* kind);

/// The whole content of `file`, after check_input_file, judged as `content`
/// says while it is read (InputError naming the file and line), hashed and
/// recorded (inputs_read()).
std::string read_input_file(const std::filesystem::path& file, const char* kind,
                            InputContent content = InputContent::binary);

/// A file this process read: as named, its size and the FNV-1a 64 hash of
/// its bytes as they were read.
struct InputRecord {
  std::filesystem::path file;
  std::uint64_t bytes = 0;
  std::uint64_t hash = 0;
};

/// The record of `file` (matched by its absolute, normal path), if read.
std::optional<InputRecord> input_read(const std::filesystem::path& file);

}  // namespace kappa
