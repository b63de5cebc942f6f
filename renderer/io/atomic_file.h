// Output files appear whole or not at all. An output to a file is written to
// an unnamed file in the file's folder (O_TMPFILE), which vanishes with the
// process however it ends, even by SIGKILL; only once complete and on disk
// is it given its name (a new file) or a name beside the file it replaces and
// renamed over it (a process killed in that instant leaves that name behind).
// Where the file
// system has no unnamed files, a named temporary (".kappa-PID-N.tmp", short
// enough beside any name) takes its place, removed on failure, on
// destruction, and on SIGINT/SIGTERM/SIGHUP.
// A symbolic link is written through, never replaced (output_target.h). A
// character device, a FIFO or one of the process's descriptors
// (/dev/stdout, "-") is written to directly: renaming a file over it would
// replace the node or the file behind the descriptor. Text goes to it as it
// is written; an image is made in memory and copied to it at commit, so a
// failed render sends nothing. Directories, sockets and block devices are
// refused for every output.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <memory>
#include <string>

namespace kappa {

/// What an output holds: text is written to a device as it comes; an image
/// is made whole first.
enum class OutputKind { text, image };

/// An unnamed file in memory (memfd), readable and writable by its path in
/// /proc (which a child process may open too), gone with the object.
class MemoryFile {
 public:
  explicit MemoryFile(const char* name);
  ~MemoryFile();
  MemoryFile(const MemoryFile&) = delete;
  MemoryFile& operator=(const MemoryFile&) = delete;
  const std::filesystem::path& path() const { return m_path; }
  int descriptor() const { return m_fd; }

 private:
  int m_fd = -1;
  std::filesystem::path m_path;
};

class AtomicOutput {
 public:
  /// Claims the output now, so an unwritable destination, or a file that
  /// could not be replaced, is refused before any work is done (throws
  /// InputError). An existing target is left untouched until commit().
  explicit AtomicOutput(const std::filesystem::path& target, OutputKind kind = OutputKind::text);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  /// Where the text or image is written: the unnamed file's path in /proc,
  /// the named temporary, or (text only) the device or FIFO itself; empty
  /// for text to a descriptor (write_temporary writes to it).
  const std::filesystem::path& temp_path() const { return m_temp; }
  /// The path as given, for messages.
  const std::filesystem::path& target() const { return m_target; }
  /// Text written straight to a device, FIFO or descriptor (no temporary).
  bool direct() const { return m_direct; }
  /// The descriptor text is written to (a copy of the one the path led to), or -1.
  int descriptor() const { return m_direct ? m_descriptor : -1; }

  /// Puts the finished output in place (throws InputError or OutputError):
  /// renames it over the target, or copies a staged image to the device or
  /// descriptor.
  void commit();

 private:
  void stage_in_folder(const std::filesystem::path& folder);
  void copy_staged_to_device();

  std::filesystem::path m_target;  ///< as given
  std::filesystem::path m_final;   ///< the file (or device) the links lead to
  std::filesystem::path m_temp;    ///< what temp_path() returns
  std::filesystem::path m_named;   ///< a named temporary in the folder, when there is one
  int m_staging = -1;    ///< the file the output is made in (unnamed, named or in memory), or -1
  bool m_unnamed = false;  ///< m_staging is an O_TMPFILE in the target's folder
  bool m_new = false;      ///< nothing was at the target when the output was claimed
  std::unique_ptr<MemoryFile> m_memory;  ///< an image for a device or descriptor, made here first
  int m_descriptor = -1;  ///< a copy of the descriptor the path led to
  bool m_direct = false;  ///< text written straight to a device, FIFO or descriptor
  int m_slot = -1;  ///< entry in the signal handler's cleanup table
  bool m_committed = false;
};

/// The output at `target`, or none when no path was given (an output not asked for).
std::unique_ptr<AtomicOutput> optional_output(const std::filesystem::path& target, OutputKind kind = OutputKind::text);

/// Writes `text` to the output's temporary and commits it (throws InputError).
void write_and_commit(AtomicOutput& output, const std::string& text);
/// Writes `text` to the output's temporary only (commit it later).
void write_temporary(AtomicOutput& output, const std::string& text);

/// The name of a temporary beside `final_name` in its folder: hidden, unique
/// to this process, at most 48 bytes whatever the name's length (NAME_MAX
/// is 255), ending with the name's extension where it is short.
std::string temporary_name(const std::filesystem::path& final_name, unsigned sequence);

/// While one lives, SIGINT, SIGTERM and SIGHUP wait: outputs committed
/// together (an image and its report) land together. A signal that came
/// meanwhile takes effect when it ends, as it would have (temporaries still
/// there are removed, and the process ends by the signal).
class SignalsHeld {
 public:
  SignalsHeld();
  ~SignalsHeld();
  SignalsHeld(const SignalsHeld&) = delete;
  SignalsHeld& operator=(const SignalsHeld&) = delete;
};

}  // namespace kappa
