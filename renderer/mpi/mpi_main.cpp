// `kappa-mpi`: kappa's commands under MPI (issue 48). `mpirun -np K
// build/kappa-mpi render SCENE ...` renders one frame on K ranks, each
// loading the scene and building the accelerator, rank 0 handing out tiles
// and writing the outputs: the image build/kappa renders, bitwise. With one
// rank every command runs as in build/kappa; the other commands refuse more.
#include <mpi.h>

#include <fcntl.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <string>
#include <variant>

#include "core/warning_log.h"
#include "renderer/cli/command_line.h"
#include "renderer/commands/render_command.h"
#include "renderer/entry/run_command.h"
#include "renderer/io/output_target.h"
#include "renderer/mpi/mpi_frame_split.h"

namespace {

/// Runs `fn` with standard error sent to /dev/null (a rank other than 0,
/// while it does what rank 0 reports: parsing the same command line).
template <class Fn>
auto without_stderr(bool silent, Fn&& fn) {
  if (!silent) return fn();
  std::fflush(stderr);
  const int saved = dup(STDERR_FILENO), null = open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (saved >= 0 && null >= 0) dup2(null, STDERR_FILENO);
  if (null >= 0) close(null);
  auto result = fn();
  std::fflush(stderr);
  if (saved >= 0) {
    dup2(saved, STDERR_FILENO);
    close(saved);
  }
  return result;
}

/// --threads' default on a rank: its host's cores shared by the ranks on
/// that host (MPI_COMM_TYPE_SHARED), at least one, within the cores the
/// rank may run on. mpirun binds each rank to one core by default (Open
/// MPI 4 with 2 ranks or fewer), which leaves a rank alone on its host one
/// thread: said once (`warn`: the default is used), with the flag that
/// gives it its share.
int default_threads_per_rank(int rank, bool warn) {
  MPI_Comm host;
  int ranks_here = 1;
  if (MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &host) == MPI_SUCCESS) {
    MPI_Comm_size(host, &ranks_here);
    MPI_Comm_free(&host);
  }
  const long host_cores = std::max(1L, sysconf(_SC_NPROCESSORS_ONLN));
  const int share = std::max(1, int(host_cores / std::max(1, ranks_here)));
  const int usable = tbb::this_task_arena::max_concurrency();  // the affinity mask's cores
  if (warn && usable < share)
    kappa::warning_log().add("kappa-mpi: rank " + std::to_string(rank) + " may run on " + std::to_string(usable) +
                             " core(s), fewer than its share of its host's " + std::to_string(host_cores) +
                             " (mpirun binds ranks to cores by default): run mpirun --bind-to none, or --map-by "
                             "slot:PE=N for N threads a rank");
  return std::min(share, usable);
}

}  // namespace

int main(int argc, char** argv) {
  std::signal(SIGPIPE, SIG_IGN);
  std::signal(SIGXFSZ, SIG_IGN);
  kappa::hold_closed_standard_descriptors();
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_MULTIPLE, &provided);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const auto finish = [](int code) {
    MPI_Finalize();
    return code;
  };
  // Rank 0's request thread and every rank's render threads call MPI.
  if (provided < MPI_THREAD_SERIALIZED) {
    if (rank == 0) std::fprintf(stderr, "kappa-mpi: error: this MPI library gives no thread support (MPI_THREAD_SERIALIZED)\n");
    return finish(1);
  }
  // Only rank 0 speaks for the job: the others' standard output goes
  // nowhere, and their warnings (of the same inputs) are counted only.
  if (rank != 0) {
    const int null = open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null >= 0) {
      dup2(null, STDOUT_FILENO);
      close(null);
    }
    kappa::warning_log().set_printing(false);
  }
  kappa::Command command;
  if (const auto code = without_stderr(rank != 0, [&] { return kappa::parse_command_line(argc, argv, command); }))
    return finish(*code);
  auto* render = std::get_if<kappa::RenderOptions>(&command);
  // Called by every rank (a collective), whatever the command.
  const int threads_per_rank = default_threads_per_rank(rank, render && render->threads == 0);
  if (render && render->threads == 0) render->threads = threads_per_rank;
  if (ranks > 1 && !render) {
    if (rank == 0)
      std::fprintf(stderr, "kappa: error: only render runs on more than one rank (mpirun -np 1, or build/kappa)\n");
    return finish(2);
  }
  bool agreed = true;  // a failure all ranks know of: each may finish
  const int code = kappa::exit_code_of([&] {
    if (render) {
      kappa::MpiFrameSplit split(MPI_COMM_WORLD);
      try {
        return kappa::run_render(*render, &split);
      } catch (const kappa::SharedFrameStopped& stop) {
        if (stop.cause) std::rethrow_exception(stop.cause);
        if (*stop.what()) std::fprintf(stderr, "kappa: error: %s\n", stop.what());
        return 2;
      } catch (...) {
        if (split.rendering()) {
          agreed = false;
          throw;
        }
        // Failed before a step the other ranks wait at (agreed_step): take
        // part in it, so that every rank stops together.
        split.all_succeeded(false);
        if (split.writer() || split.writer_succeeded()) throw;
        return 2;  // the writer reports the same failure
      }
    }
    return kappa::run_command(command);
  });
  // A rank that failed where the others do not know it (rendering, writing)
  // ends the job: the others would wait for it forever.
  if (code != 0 && !agreed && ranks > 1) MPI_Abort(MPI_COMM_WORLD, code);
  return finish(code);
}
