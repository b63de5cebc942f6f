#include "renderer/entry/run_command.h"

#include <variant>

#include "renderer/commands/bench_command.h"
#include "renderer/commands/calibrate_command.h"
#include "renderer/commands/cast_command.h"
#include "renderer/commands/converge_command.h"
#include "renderer/commands/render_command.h"
#include "renderer/commands/sweep_command.h"

namespace kappa {

int run_command(const Command& command) {
  struct Run {
    int operator()(const RenderOptions& o) const { return run_render(o); }
    int operator()(const CastOptions& o) const { return run_cast(o); }
    int operator()(const BenchOptions& o) const { return run_bench(o); }
    int operator()(const CalibrateOptions& o) const { return run_calibrate(o); }
    int operator()(const ConvergeOptions& o) const { return run_converge(o); }
    int operator()(const SweepOptions& o) const { return run_sweep(o); }
  };
  return std::visit(Run{}, command);
}

}  // namespace kappa
