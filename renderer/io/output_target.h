// Where an output path leads, decided before any work is done. Symbolic links
// are followed one at a time, as the kernel would, and never replaced: a link
// is written through to the file it resolves to, and one that resolves to
// nothing (dangling, a loop, /dev/stdout while descriptor 1 is closed) is
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
/// refused are a link that resolves to nothing, a folder that does not exist,
/// a directory, socket or block device, a closed descriptor or one open only
/// for reading, and a file to make or replace in /dev or /proc (no output is
/// ever renamed there).
OutputTarget resolve_output_target(const std::filesystem::path& given);

/// "standard output", "standard error" or "descriptor N", for messages.
std::string descriptor_name(int descriptor);

}  // namespace kappa
