#include "pilot_replay.h"

#include <vector>

#include "core/parallel.h"

namespace kappa {

void for_each_tile_run(std::span<const PilotSegment> segments,
                       const std::function<void(std::size_t begin, std::size_t end)>& walk) {
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i < segments.size(); ++i)
    if (i == 0 || segments[i].tile != segments[i - 1].tile) starts.push_back(i);
  starts.push_back(segments.size());
  kappa::parallel_for(std::size_t(0), starts.size() - 1, [&](std::size_t run) { walk(starts[run], starts[run + 1]); });
}

}  // namespace kappa
