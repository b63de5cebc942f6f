// A frame shared by the ranks of an MPI job (issue 48): rank 0 hands out
// tiles from a thread of its own while its render threads take tiles too,
// and after the pass gathers every rank's tiles, estimates and counts.
// kappa-mpi only: build/kappa does not link MPI.
#pragma once

#include <mpi.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include "renderer/render/frame_split.h"

namespace kappa {

class MpiFrameSplit final : public FrameSplit {
 public:
  /// Over `comm` (duplicated: Kappa's messages never meet another library's).
  explicit MpiFrameSplit(MPI_Comm comm);
  ~MpiFrameSplit() override;

  int process() const override { return m_rank; }
  int processes() const override { return m_ranks; }
  bool all_succeeded(bool succeeded) override;
  bool writer_succeeded() const override { return m_writer_succeeded; }

  void begin_pass(std::size_t tiles) override;
  std::optional<std::size_t> next_tile() override;
  void end_pass(Film* film, std::span<double> tile_estimates, std::span<std::uint64_t> counts) override;
  void share_pass_state(int width, int height, std::size_t bytes,
                        const std::function<void(std::size_t, std::byte*)>& pack,
                        const std::function<void(std::size_t, const std::byte*)>& unpack) override;
  std::uint64_t writer_value(std::uint64_t value) override;
  std::string writer_text(const std::string& text) override;
  void sum_on_writer(std::span<std::uint64_t> values) override;
  std::vector<ProcessShare> shares() const override { return m_shares; }
  std::vector<double> tile_seconds() const override { return m_tile_seconds_sum; }
  void predict_tile_costs(std::vector<double> costs) override { m_predicted = std::move(costs); }
  std::vector<double> first_pass_costs() const override { return m_first_pass_costs; }

  void rendering_begins() override { m_rendering = true; }
  /// Past the last agreement: from here a rank that fails cannot meet the
  /// others at one, and the job must end (MPI_Abort).
  bool rendering() const { return m_rendering; }
  /// Tiles this rank rendered in the last pass.
  std::size_t tiles_rendered() const { return m_mine.size(); }

 private:
  void coordinate();  // rank 0's thread: answers requests until every other rank is done
  void gather_shares(std::uint64_t rays, double seconds);  // this pass's, added to m_shares on rank 0
  void gather_pixels(Film& film);                          // the other ranks' tiles, into rank 0's film

  /// A render thread's tile in progress, timed (the next pass's order).
  struct TileClock {
    const MpiFrameSplit* owner = nullptr;
    std::size_t current = 0;
    std::chrono::steady_clock::time_point began;
    void start(const MpiFrameSplit* split, std::size_t tile);
  };
  static thread_local TileClock t_clock;

  MPI_Comm m_comm = MPI_COMM_NULL;
  int m_rank = 0, m_ranks = 1;
  bool m_writer_succeeded = true;
  bool m_rendering = false;
  std::size_t m_tiles = 0;
  std::atomic<std::size_t> m_next{0};  // rank 0: the next of m_order to hand out
  std::mutex m_mutex;                  // a request and its answer; m_mine
  bool m_exhausted = false;            // other ranks: rank 0 has no tile left
  bool m_asked = false;                // other ranks: a request is out, its answer to come in m_answer
  long long m_answer = -1;
  MPI_Request m_answer_request = MPI_REQUEST_NULL;
  std::vector<std::size_t> m_mine;     // the tiles this rank rendered, as handed out
  std::thread m_coordinator;
  std::string m_host;                            // MPI_Get_processor_name
  std::chrono::steady_clock::time_point m_pass_start;
  std::vector<ProcessShare> m_shares;            // rank 0: every rank's, summed over the passes
  std::vector<std::size_t> m_order;              // rank 0: the order tiles go out in this pass
  std::vector<double> m_predicted;               // rank 0: each tile's predicted cost, for the first pass
  std::vector<double> m_first_pass_costs;        // rank 0: m_predicted, once the first pass went by it
  std::vector<double> m_tile_seconds;            // each tile's seconds in its last pass (rank 0: all)
  std::vector<double> m_tile_seconds_sum;        // rank 0: each tile's, summed over the passes
};

}  // namespace kappa
