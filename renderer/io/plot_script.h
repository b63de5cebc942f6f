// The plots of `kappa converge --plot` and `kappa sweep --plot`: a script of
// tools/ run with /usr/bin/python3, where Debian's python3-matplotlib lives
// (not the python3 first on PATH).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "renderer/io/atomic_file.h"

namespace kappa {

/// Runs tools/`script` with /usr/bin/python3 and `args`. Each script takes
/// `--check` (exit 0 when it can plot, 3 when matplotlib is missing), which a
/// command runs before its work so that a missing package fails at once.
/// Throws InputError naming what is missing (python3, python3-matplotlib,
/// the script) and std::runtime_error when the script fails otherwise.
void run_plot_script(const std::string& script, const std::vector<std::string>& args);

/// The outputs of a command that writes JSON (--json) and may plot it
/// (--plot, a PNG drawn from that JSON by a script of tools/). Claimed when
/// made, before the work: an unwritable path or a missing matplotlib fails
/// at once. finish() writes the JSON, draws the plot from it (from the JSON's
/// temporary, or from a copy in memory when there is no --json or it names a
/// device or FIFO, which the script could not read back) and commits both
/// together. Empty paths: that output is not wanted.
class JsonAndPlot {
 public:
  JsonAndPlot(const std::filesystem::path& json, const std::filesystem::path& plot, std::string script);
  void finish(const std::string& text);

 private:
  std::string m_script;
  std::unique_ptr<AtomicOutput> m_json, m_plot;
  std::unique_ptr<MemoryFile> m_plot_json;  ///< the JSON the script reads when m_json cannot be read back
};

}  // namespace kappa
