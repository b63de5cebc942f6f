// The plots of `kappa converge --plot` and `kappa sweep --plot`: a script of
// tools/ run with /usr/bin/python3, where Debian's python3-matplotlib lives
// (not the python3 first on PATH).
#pragma once

#include <string>
#include <vector>

namespace kappa {

/// Runs tools/`script` with /usr/bin/python3 and `args`. Each script takes
/// `--check` (exit 0 when it can plot, 3 when matplotlib is missing), which a
/// command runs before its work so that a missing package fails at once.
/// Throws InputError naming what is missing (python3, python3-matplotlib,
/// the script) and std::runtime_error when the script fails otherwise.
void run_plot_script(const std::string& script, const std::vector<std::string>& args);

}  // namespace kappa
