// Output files appear whole or not at all: written to a temporary file in the
// target folder and renamed over the target only once complete. The temporary
// is removed on failure, on destruction, and on SIGINT/SIGTERM/SIGHUP.
#pragma once

#include <filesystem>
#include <string>

namespace kappa {

class AtomicOutput {
 public:
  /// Creates the temporary file now, so an unwritable destination is refused
  /// before any work is done (throws InputError). An existing target is left
  /// untouched until commit().
  explicit AtomicOutput(const std::filesystem::path& target);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  const std::filesystem::path& temp_path() const { return m_temp; }
  const std::filesystem::path& target() const { return m_target; }

  /// Renames the finished temporary over the target (throws InputError).
  void commit();

 private:
  std::filesystem::path m_target, m_temp;
  int m_slot = -1;  ///< entry in the signal handler's cleanup table
  bool m_committed = false;
};

/// Writes `text` to the output's temporary and commits it (throws InputError).
void write_and_commit(AtomicOutput& output, const std::string& text);

}  // namespace kappa
