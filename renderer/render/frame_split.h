// A frame shared by several processes (kappa-mpi's ranks, issue 48): which
// tiles this one renders (TileSchedule), which one writes the outputs, and
// the points where they must agree before going on. Every process loads the
// same scene and builds the same accelerator; the writer (process 0) makes
// every per-frame choice. Nothing here knows MPI: renderer/mpi/ implements it.
#pragma once

#include <cstdint>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "renderer/render/tile_schedule.h"

namespace kappa {

/// One process's share of a shared frame, over its passes (the report's
/// `mpi.per_rank`): where it ran, with how many threads, how many tiles and
/// rays it rendered, and the seconds from each pass's start to its last tile.
struct ProcessShare {
  int process = 0;
  std::string host;
  int threads = 0;
  std::uint64_t tiles = 0, rays = 0;
  double time_s = 0;
};

class FrameSplit : public TileSchedule {
 public:
  virtual int process() const = 0;    ///< 0 .. processes() - 1
  virtual int processes() const = 0;
  /// Process 0 writes the image and the report; the others only render.
  bool writer() const { return process() == 0; }
  /// Every process calls this at the same point with whether its own step
  /// succeeded; true if every process's did.
  virtual bool all_succeeded(bool succeeded) = 0;
  /// Whether the writer's step succeeded, at the last all_succeeded.
  virtual bool writer_succeeded() const = 0;
  /// Past the last agreement (the film): from here a process that fails
  /// cannot tell the others at one, and the frame must end for all.
  virtual void rendering_begins() = 0;
  /// The writer's `text` (a choice it made for all: the accelerator `auto`
  /// chose, the resolution `--grid-res model` chose), on every process;
  /// called by all at the same point.
  virtual std::string writer_text(const std::string& text) = 0;
  /// On the writer, after the last pass: every process's share, by process
  /// (empty on the others).
  virtual std::vector<ProcessShare> shares() const = 0;
  /// On the writer, after the last pass: each tile's seconds on the thread
  /// that rendered it, summed over the passes, by tile (empty on the others).
  virtual std::vector<double> tile_seconds() const = 0;
  /// On the writer, before the first pass: each tile's predicted cost
  /// (tile_costs.h, from a pilot), for the first pass's order, the costliest
  /// first. Without, the first pass goes in tile order; later passes go by
  /// the tiles' measured seconds either way.
  virtual void predict_tile_costs(std::vector<double> costs) = 0;
  /// On the writer, after the first pass: the predicted costs it handed its
  /// tiles out by, or empty where it went in tile order (the report's).
  virtual std::vector<double> first_pass_costs() const = 0;
};

/// Thrown on every process where a shared frame stops at an agreed step
/// (agreed_step), so that all of them end together and none waits for
/// another: `cause` is the failure this process reports (its own, when it
/// is the writer or failed alone), `message` a line of its own ("another
/// rank failed"), or neither when another process reports it.
struct SharedFrameStopped : std::runtime_error {
  SharedFrameStopped(std::exception_ptr cause, const std::string& message)
      : std::runtime_error(message), cause(std::move(cause)) {}
  std::exception_ptr cause;
};

/// Runs `step` (loading, building, claiming the outputs: what may fail on
/// one process alone, a file missing on one host) and has every process of
/// `split` agree on its success before any goes on. Without a split, or
/// with one process, just `step()`. A failure is reported once: by the
/// writer if it failed, else by each process that failed, the writer
/// adding that another rank did.
template <class Step>
auto agreed_step(FrameSplit* split, Step&& step) -> decltype(step()) {
  if (!split || split->processes() == 1) return step();
  std::optional<decltype(step())> value;
  std::exception_ptr failure;
  try {
    value.emplace(step());
  } catch (...) {
    failure = std::current_exception();
  }
  const bool all = split->all_succeeded(!failure);
  if (failure) throw SharedFrameStopped(split->writer() || split->writer_succeeded() ? failure : nullptr, "");
  if (!all) throw SharedFrameStopped(nullptr, split->writer() ? "another rank failed (its message is above)" : "");
  return std::move(*value);
}

}  // namespace kappa
