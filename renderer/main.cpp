// `kappa`: parse the command line, run the one subcommand it names.
#include "renderer/cli/command_line.h"
#include "renderer/entry/run_command.h"
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
  return kappa::exit_code_of([&] { return kappa::run_command(command); });
}
