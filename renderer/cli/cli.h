// The `kappa` command line: parses, then calls the library. Exit codes: 0
// success, 2 bad input or options (one line on stderr), 1 internal error.
#pragma once

namespace kappa {

int run_cli(int argc, char** argv);

}  // namespace kappa
