// Where an output path leads, decided before any work is done. Symbolic links
// are followed one at a time, as the kernel would, and never replaced: a link
// is written through to the file it resolves to, made if it does not exist
// yet (as the shell's `>` and oiiotool do); a loop, a link into a folder
// that does not exist and /dev/stdout while descriptor 1 is closed are
// refused. A path that leads to one of this process's descriptors
// (/dev/stdout, /dev/fd/N, /proc/self/fd/N, or "-") is that descriptor, not
// the file behind it: a report into `>> log` appends to the log instead of
// renaming a new file over it.
#pragma once

#include <filesystem>

namespace kappa {

struct OutputTarget {
  enum class Kind {
    new_file,    ///< nothing there yet: created
    file,        ///< an existing regular file: replaced by rename
    device,      ///< a character device or FIFO: written in place
    descriptor,  ///< an open descriptor of this process: written in place
  };
  Kind kind = Kind::new_file;
  /// The file the links lead to (new_file, file, device); empty for a descriptor.
  std::filesystem::path path;
  int descriptor = -1;  ///< for Kind::descriptor
};

/// Resolves `given` (throws InputError naming `given` and why, exit 2):
/// refused are a loop of links, a folder that does not exist,
/// a directory, socket or block device, a closed descriptor or one open only
/// for reading, and a file to make or replace in /dev or /proc (no output is
/// ever renamed there).
OutputTarget resolve_output_target(const std::filesystem::path& given);

/// Whether `given` leads to a device, FIFO or descriptor (written as a
/// stream, whatever its name ends in); false for files and for paths
/// resolve_output_target refuses.
bool leads_to_stream(const std::filesystem::path& given);

/// Opens /dev/null read-only on each of descriptors 0, 1 and 2 that is
/// closed, and remembers them as closed: resolve_output_target still refuses
/// them as closed, and no file opened later takes their number. Called once,
/// first thing in main().
void hold_closed_standard_descriptors();

/// "standard output", "standard error" or "descriptor N", for messages.
std::string descriptor_name(int descriptor);

}  // namespace kappa
