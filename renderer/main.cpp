// `kappa`: parse the command line, run the one subcommand it names.
#include "renderer/cli/command_line.h"
#include "renderer/commands/bench_command.h"
#include "renderer/commands/calibrate_command.h"
#include "renderer/commands/cast_command.h"
#include "renderer/commands/converge_command.h"
#include "renderer/commands/render_command.h"
#include "renderer/commands/sweep_command.h"
#include "renderer/io/output_target.h"

#include <csignal>

int main(int argc, char** argv) {
  // A report written to a pipe whose reader went away fails its write
  // (exit 1) instead of killing the process.
  std::signal(SIGPIPE, SIG_IGN);
  // A write past the file-size limit (RLIMIT_FSIZE) fails with EFBIG and is
  // reported, its temporary removed, instead of killing the process and
  // leaving the temporary behind.
  std::signal(SIGXFSZ, SIG_IGN);
  // A closed standard descriptor is held by /dev/null, read-only, so that no
  // file opened later (an output being made) becomes standard output or
  // error and receives a report or a warning.
  kappa::hold_closed_standard_descriptors();
  kappa::Command command;
  if (const auto exit_code = kappa::parse_command_line(argc, argv, command)) return *exit_code;
  return kappa::exit_code_of([&] {
    struct Run {
      int operator()(const kappa::RenderOptions& o) const { return kappa::run_render(o); }
      int operator()(const kappa::CastOptions& o) const { return kappa::run_cast(o); }
      int operator()(const kappa::BenchOptions& o) const { return kappa::run_bench(o); }
      int operator()(const kappa::CalibrateOptions& o) const { return kappa::run_calibrate(o); }
      int operator()(const kappa::ConvergeOptions& o) const { return kappa::run_converge(o); }
      int operator()(const kappa::SweepOptions& o) const { return kappa::run_sweep(o); }
    };
    return std::visit(Run{}, command);
  });
}
