// The `kappa` command line: which subcommand, with which options. Exit codes
// (docs/command-line.md): 0 success, 2 bad input or options (one line on stderr), 1
// internal error.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <variant>

#include "renderer/cli/options.h"

namespace kappa {

using Command = std::variant<RenderOptions, CastOptions, BenchOptions, CalibrateOptions, ConvergeOptions, SweepOptions>;

/// Parses argv into `command`. Returns the exit code when the process should
/// end here: after --help or --version (0), or for bad options (2, with one
/// line on stderr); nullopt when `command` is ready to run.
std::optional<int> parse_command_line(int argc, char** argv, Command& command);

/// `base` with render's option --KEY set to `value`, validated as on render's
/// command line (kappa converge --vary); throws InputError for a key converge
/// does not take or a bad value.
RenderOptions vary_render_option(const RenderOptions& base, const std::string& key, const std::string& value);

/// Runs a command and turns what it throws into the exit code and the one
/// line on stderr docs/command-line.md promises.
int exit_code_of(const std::function<int()>& run);

}  // namespace kappa
