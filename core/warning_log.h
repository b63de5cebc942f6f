// The warnings of a run, as the user reads them: each kind printed for its
// first few occurrences, then counted, and one line per kind at the end
// ("... and N more like it"), so that 20,000 uses of an undefined material
// print six lines, not 20,000. The report lists every kind with its count.
// A warning's kind is its text without its location and with its quoted
// names and numbers masked: "a.obj:12: material 'red' is not defined" and
// "b.obj:40: material 'blue' is not defined" are one kind.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace kappa {

/// How many warnings of one kind are printed before the rest are counted.
inline constexpr std::uint64_t kWarningsShownPerKind = 5;

struct WarningKind {
  std::string kind;   ///< the text, its location dropped and names and numbers masked
  std::string first;  ///< the first warning of the kind, as printed
  std::uint64_t count = 0;
};

class WarningLog {
 public:
  /// Prints "kappa: warning: TEXT" unless kWarningsShownPerKind of its kind
  /// were printed already; counts it either way. Thread-safe.
  void add(const std::string& text);
  /// Prints "kappa: warning: ... and N more like it: KIND" for each kind with
  /// warnings not printed, once (later calls print only what came since).
  void finish();
  /// Every kind seen, in the order first seen.
  std::vector<WarningKind> kinds() const;
  /// Off: warnings are counted, not printed (kappa-mpi's ranks but the
  /// writer, which prints the same warnings of the same inputs once).
  void set_printing(bool on) { m_printing = on; }

 private:
  struct Entry {
    WarningKind kind;
    std::uint64_t summarised = 0;  ///< warnings already counted in a summary line
  };
  mutable std::mutex m_mutex;
  std::vector<Entry> m_entries;
  std::atomic<bool> m_printing{true};
};

/// The process's log, where every command's warnings go.
WarningLog& warning_log();

/// Hands each of `warnings` to warning_log().
void print_warnings(const std::vector<std::string>& warnings);

/// `text`'s kind: without a leading "file: " or "file:line: ", with each
/// '...' quotation and each run of digits masked.
std::string warning_kind(const std::string& text);

}  // namespace kappa
