#include "resolution_choice.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <atomic>

#include <cmath>
#include <functional>
#include <limits>

#include "accel/grid_traverse.h"
#include "accel/triangle.h"
#include "core/check.h"
#include "core/input_error.h"
#include "core/parallel.h"
#include "pilot_replay.h"

namespace kappa {

std::size_t smallest_within(std::span<const Candidate> candidates, double tolerance) {
  double least = std::numeric_limits<double>::infinity();
  for (const Candidate& c : candidates) least = std::min(least, c.total_s());
  std::size_t best = 0;
  bool found = false;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (!(candidates[i].total_s() <= least * (1 + tolerance))) continue;
    if (!found || candidates[i].res.cells() < candidates[best].res.cells()) best = i, found = true;
  }
  return best;
}

void search_unimodal(std::size_t count, std::size_t start, const std::function<double(std::size_t)>& cost,
                     double tolerance) {
  if (count == 0) return;
  // Over the budget (an infinite cost) at the start: go down until one fits.
  while (std::isinf(cost(start)) && start > 0) --start;
  std::size_t at = start;
  double least = cost(at);
  const auto downhill = [&](int step) {
    while (true) {
      const std::ptrdiff_t next = std::ptrdiff_t(at) + step;
      if (next < 0 || next >= std::ptrdiff_t(count)) return;
      const double c = cost(std::size_t(next));
      if (!(c < least)) return;
      at = std::size_t(next);
      least = c;
    }
  };
  downhill(+1);
  if (at == start) downhill(-1);
  // The 2 % rule looks below the least: smaller grids whose cost is within
  // the tolerance (costs rise monotonically below the minimum).
  for (std::size_t i = at; i-- > 0;)
    if (!(cost(i) <= least * (1 + tolerance))) break;
}

namespace {

/// The whole grid's bytes at `theta_tot` references: offsets, occupancy
/// bits and the reference array, as the grid counts its own.
double whole_grid_bytes(std::uint64_t cells, double theta_tot) {
  return double((cells + 1) * sizeof(std::uint32_t) + (cells + 63) / 64 * sizeof(std::uint64_t)) +
         theta_tot * double(sizeof(TriangleId));
}

}  // namespace

std::optional<double> cold_steps_spp(const TimeModel& model, double frame_spp) {
  if (model.form != ModelForm::coherent) return std::nullopt;
  return frame_spp;
}

std::array<QueryLoad, kRenderClasses> count_segments(const UniformGrid& grid, std::span<const PilotSegment> segments,
                                                     std::optional<double> whole_theta_tot, std::optional<double> frame_spp) {
  const double triangles = double(grid.info().N * sizeof(Triangle));
  const double bytes = whole_theta_tot ? whole_grid_bytes(grid.info().resolution.cells(), *whole_theta_tot) : double(grid.bytes());
  const double references =
      whole_theta_tot ? *whole_theta_tot * double(sizeof(TriangleId)) : double(grid.reference_bytes());
  return replay_segments(
      segments,
      [&](const PilotSegment& s, auto& recorder) {
        grid.count_closest_walk(s.ray, s.hit ? std::optional<float>(s.t_hit) : std::nullopt, recorder);
        return s.hit;
      },
      bytes + triangles, references + triangles, frame_spp);
}

namespace {

/// Marks each cell a walk enters (accel/recorder.h), into a bitset the
/// threads share.
struct CellMarks {
  std::uint64_t* bits;
  template <class BoxFn>
  void cell(std::uint64_t c, int, BoxFn&&) {
    std::uint64_t& word = bits[c >> 6];
    const std::uint64_t bit = std::uint64_t(1) << (c & 63);
    // Most visits are to cells marked already: read before the atomic write.
    if (!(std::atomic_ref<std::uint64_t>(word).load(std::memory_order_relaxed) & bit))
      std::atomic_ref<std::uint64_t>(word).fetch_or(bit, std::memory_order_relaxed);
  }
  void test() {}
  void hit() {}
  void finish(const WalkCounts&, const WalkSegment&) {}
};

}  // namespace

std::vector<std::uint64_t> visited_cells(const UniformGrid& grid, std::span<const PilotSegment> segments) {
  std::vector<std::uint64_t> bits((grid.cell_count() + 63) / 64, 0);
  kappa::parallel_for(tbb::blocked_range<std::size_t>(0, segments.size(), 1024), [&](const auto& range) {
    CellMarks marks{bits.data()};
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      const PilotSegment& s = segments[i];
      grid.count_closest_walk(s.ray, s.hit ? std::optional<float>(s.t_hit) : std::nullopt, marks);
    }
  });
  return bits;
}

std::unique_ptr<UniformGrid> counting_grid(std::span<const Triangle> triangles, GridOptions options,
                                           std::span<const PilotSegment> segments) {
  options.cells_to_fill = [segments](const UniformGrid& empty) { return visited_cells(empty, segments); };
  return std::make_unique<UniformGrid>(triangles, options);
}

std::unique_ptr<UniformGrid> counting_grid(std::span<const Triangle> triangles, const GridResolution& res,
                                           std::span<const PilotSegment> segments, std::uint64_t max_bytes) {
  GridOptions options;
  options.resolution = res;
  options.max_bytes = max_bytes;
  return counting_grid(triangles, std::move(options), segments);
}

Candidate evaluate_candidate(const UniformGrid& grid, std::span<const PilotSegment> segments, const ChoiceSettings& settings,
                             const OccupancyModel* occupancy) {
  const GridInfo& info = grid.info();
  Candidate c;
  c.res = info.resolution;
  c.lambda = info.N > 0 ? double(info.resolution.cells()) / double(info.N) : 0.0;
  double grid_bytes = double(grid.bytes());
  std::optional<double> whole_theta_tot;  // a partial grid's: the whole grid's, predicted
  if (info.partial) {
    KAPPA_CHECK(occupancy != nullptr);
    const double theta = occupancy->theta_tot(info.cell_size);
    c.theta_tot = std::isfinite(theta) ? std::uint64_t(std::llround(theta)) : std::numeric_limits<std::uint64_t>::max();
    whole_theta_tot = double(c.theta_tot);
    grid_bytes = whole_grid_bytes(info.resolution.cells(), *whole_theta_tot);
  } else {
    c.theta_tot = info.theta_tot;
  }
  c.bytes = std::uint64_t(std::min(grid_bytes + settings.stats_bytes_per_cell * double(info.resolution.cells()), 1.8e19));
  const auto loads =
      count_segments(grid, segments, whole_theta_tot, cold_steps_spp(*settings.traversal, settings.frame_spp));
  // The model predicts thread-seconds (as calibrate times them); the frame's
  // threads share them, while the build's model gives its wall time.
  for (std::size_t k = 0; k < kRenderClasses; ++k)
    c.traversal_s += settings.traversal->seconds(loads[k]) * settings.rays_scale[k] / double(std::max(1, settings.threads));
  c.build_s = settings.build->seconds(double(info.N), double(c.theta_tot), double(info.resolution.cells()),
                                      settings.threads);
  return c;
}

std::vector<GridResolution> candidate_resolutions(std::span<const Triangle> triangles) {
  const GridBox box = grid_box(triangles);
  const OccupancyModel occupancy(triangles);
  const double N = std::max(1.0, occupancy.N);
  std::vector<GridResolution> out;
  for (int k = kMinStep; k <= kMaxStep; ++k) {
    const double cells = std::min(32.0 * std::pow(2.0, 0.5 * k) * N, double(std::numeric_limits<std::uint32_t>::max() - 2));
    const GridResolution r = bounded_resolution(occupancy, box.extent(), choose_resolution(box.extent(), cells));
    if (std::find(out.begin(), out.end(), r) == out.end()) out.push_back(r);
  }
  std::sort(out.begin(), out.end(), [](const GridResolution& a, const GridResolution& b) { return a.cells() < b.cells(); });
  return out;
}

ResolutionChoice choose_resolution_by_model(std::span<const Triangle> triangles, std::span<const PilotSegment> segments,
                                            const ChoiceSettings& settings, bool exhaustive, const UniformGrid* whole,
                                            bool build_chosen) {
  const std::vector<GridResolution> resolutions = candidate_resolutions(triangles);
  const OccupancyModel occupancy(triangles);
  const double N = std::max(1.0, occupancy.N);
  ResolutionChoice choice;
  constexpr double kNotFit = std::numeric_limits<double>::infinity();
  std::vector<double> total(resolutions.size(), -1.0);  // -1: not evaluated yet
  const auto evaluate = [&](std::size_t i) {
    if (total[i] >= 0) return total[i];
    Candidate c;
    if (whole && whole->info().resolution == resolutions[i]) {
      c = evaluate_candidate(*whole, segments, settings);
    } else {
      std::unique_ptr<UniformGrid> grid;
      try {
        grid = counting_grid(triangles, resolutions[i], segments, settings.max_bytes);
      } catch (const InputError& e) {
        choice.skipped.push_back(resolutions[i].to_string() + ": " + e.what());
        return total[i] = kNotFit;
      }
      c = evaluate_candidate(*grid, segments, settings, &occupancy);
    }
    if (c.bytes > settings.max_bytes) {
      choice.skipped.push_back(resolutions[i].to_string() + ": the grid and its per-cell statistics need " +
                               std::to_string(c.bytes) + " bytes, over --grid-max-bytes");
      return total[i] = kNotFit;
    }
    choice.evaluated.push_back(c);
    return total[i] = c.total_s();
  };

  if (exhaustive) {
    for (std::size_t i = 0; i < resolutions.size(); ++i) evaluate(i);
  } else {
    // Start nearest lambda = 32 (the default's density), walk downhill.
    std::size_t start = 0;
    for (std::size_t i = 0; i < resolutions.size(); ++i)
      if (std::abs(std::log(double(resolutions[i].cells()) / (32 * N))) <
          std::abs(std::log(double(resolutions[start].cells()) / (32 * N))))
        start = i;
    search_unimodal(resolutions.size(), start, evaluate, settings.tolerance);
  }
  if (choice.evaluated.empty())
    throw InputError("--grid-res model: no candidate resolution fits --grid-max-bytes (" +
                     std::to_string(settings.max_bytes) + " bytes)");
  choice.chosen = smallest_within(choice.evaluated, settings.tolerance);
  if (build_chosen) build_chosen_grid(choice, triangles, settings, whole);
  return choice;
}

void build_chosen_grid(ResolutionChoice& choice, std::span<const Triangle> triangles, const ChoiceSettings& settings,
                       const UniformGrid* whole) {
  // The chosen one's whole grid: `whole` itself, or built now. Its bytes
  // were predicted (eq 19): one that does not fit after all gives way to the
  // next choice.
  while (!choice.evaluated.empty()) {
    choice.chosen = smallest_within(choice.evaluated, settings.tolerance);
    const GridResolution& res = choice.evaluated[choice.chosen].res;
    if (whole && whole->info().resolution == res) return;
    GridOptions options;
    options.resolution = res;
    options.max_bytes = settings.max_bytes;
    try {
      choice.grid = std::make_unique<UniformGrid>(triangles, options);
      return;
    } catch (const InputError& e) {
      choice.skipped.push_back(res.to_string() + ": " + e.what());
      choice.evaluated.erase(choice.evaluated.begin() + std::ptrdiff_t(choice.chosen));
    }
  }
  throw InputError("--grid-res model: no candidate resolution fits --grid-max-bytes (" +
                   std::to_string(settings.max_bytes) + " bytes)");
}

}  // namespace kappa
