// Output files appear whole or not at all: written to a temporary file beside
// the file written and renamed over it only once complete. The temporary is
// removed on failure, on destruction, and on SIGINT/SIGTERM/SIGHUP.
// A symbolic link is written through, never replaced (output_target.h). A
// text output (a JSON report) that names a character device, a FIFO or one of
// the process's descriptors (/dev/stdout, "-") is written to it directly:
// renaming a temporary over it would replace the node or the file behind the
// descriptor. Images must be regular files or new paths; directories, sockets
// and block devices are refused for every output.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

namespace kappa {

/// What an output holds: text may go to a device or FIFO; an image may not.
enum class OutputKind { text, image };

class AtomicOutput {
 public:
  /// Creates the temporary file now, so an unwritable destination is refused
  /// before any work is done (throws InputError). An existing target is left
  /// untouched until commit().
  explicit AtomicOutput(const std::filesystem::path& target, OutputKind kind = OutputKind::text);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  /// Where the text or image is written: the temporary, or the device or
  /// FIFO itself (empty for a descriptor: write_temporary writes to it).
  const std::filesystem::path& temp_path() const { return m_temp; }
  /// The path as given, for messages.
  const std::filesystem::path& target() const { return m_target; }
  /// Written straight to a device, FIFO or descriptor (no temporary).
  bool direct() const { return m_direct; }
  /// The descriptor written to (a copy of the one the path led to), or -1.
  int descriptor() const { return m_descriptor; }

  /// Renames the finished temporary over the target (throws InputError).
  void commit();

 private:
  std::filesystem::path m_target;  ///< as given
  std::filesystem::path m_final;   ///< the file the links lead to, renamed over at commit
  std::filesystem::path m_temp;
  int m_descriptor = -1;
  bool m_direct = false;  ///< written straight to a device, FIFO or descriptor: no temporary
  int m_slot = -1;  ///< entry in the signal handler's cleanup table
  bool m_committed = false;
};

/// The output at `target`, or none when no path was given (an output not asked for).
std::unique_ptr<AtomicOutput> optional_output(const std::filesystem::path& target, OutputKind kind = OutputKind::text);

/// Writes `text` to the output's temporary and commits it (throws InputError).
void write_and_commit(AtomicOutput& output, const std::string& text);
/// Writes `text` to the output's temporary only (commit it later).
void write_temporary(AtomicOutput& output, const std::string& text);

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
