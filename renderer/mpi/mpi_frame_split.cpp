#include "renderer/mpi/mpi_frame_split.h"

#include <algorithm>
#include <cstring>

#include "core/check.h"
#include "core/thread_limit.h"
#include "renderer/render/film.h"
#include "renderer/render/tile_costs.h"

namespace kappa {
namespace {

constexpr int kTagRequest = 1;  // a rank asks for a tile
constexpr int kTagTile = 2;     // rank 0's answer: a tile, or -1 for none left
constexpr int kTagDone = 3;     // a rank has rendered all its tiles of the pass
// Rank 0's coordinator naps between looks for a request, from kFirstNap,
// doubling while none comes, to kLongestNap.
constexpr auto kFirstNap = std::chrono::microseconds(20);
constexpr auto kLongestNap = std::chrono::microseconds(1000);

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

/// The film's channels, in one order every rank uses, with their components.
std::vector<std::pair<std::vector<float>*, int>> channels(Film& film) {
  std::vector<std::pair<std::vector<float>*, int>> c = {{&film.rgb, 3}};
  for (auto [v, n] : {std::pair{&film.albedo, 3}, {&film.normal, 3}, {&film.depth, 1}, {&film.cost_cells, 1},
                      {&film.cost_tests, 1}, {&film.variance, 3}, {&film.spp, 1}})
    if (!v->empty()) c.emplace_back(v, n);
  return c;
}

/// Calls `fn(pixel)` for every pixel of `tile` of a width x height frame, row by row.
template <class Fn>
void for_each_pixel(int width, int height, std::size_t tile, Fn&& fn) {
  const int tiles_x = (width + kTileSize - 1) / kTileSize;
  const int x0 = int(tile % std::size_t(tiles_x)) * kTileSize, y0 = int(tile / std::size_t(tiles_x)) * kTileSize;
  for (int y = y0; y < std::min(y0 + kTileSize, height); ++y)
    for (int x = x0; x < std::min(x0 + kTileSize, width); ++x) fn(std::size_t(y) * std::size_t(width) + std::size_t(x));
}

/// A contiguous type of `bytes` bytes: MPI counts are ints, so pixels are
/// counted as pixels, not bytes or floats (a 16k x 16k frame has 2^28).
class PixelType {
 public:
  explicit PixelType(std::size_t bytes) {
    check(MPI_Type_contiguous(int(bytes), MPI_BYTE, &m_type), "MPI_Type_contiguous");
    check(MPI_Type_commit(&m_type), "MPI_Type_commit");
  }
  ~PixelType() { MPI_Type_free(&m_type); }
  PixelType(const PixelType&) = delete;
  PixelType& operator=(const PixelType&) = delete;
  operator MPI_Datatype() const { return m_type; }

 private:
  MPI_Datatype m_type = MPI_DATATYPE_NULL;
};

}  // namespace

MpiFrameSplit::MpiFrameSplit(MPI_Comm comm) {
  check(MPI_Comm_dup(comm, &m_comm), "MPI_Comm_dup");
  MPI_Comm_rank(m_comm, &m_rank);
  MPI_Comm_size(m_comm, &m_ranks);
  char host[MPI_MAX_PROCESSOR_NAME] = {};
  int length = 0;
  if (MPI_Get_processor_name(host, &length) == MPI_SUCCESS) m_host.assign(host, std::size_t(std::max(length, 0)));
}

MpiFrameSplit::~MpiFrameSplit() {
  if (m_coordinator.joinable()) m_coordinator.join();
  MPI_Comm_free(&m_comm);
}

bool MpiFrameSplit::all_succeeded(bool succeeded) {
  std::vector<int> all(std::size_t(m_ranks), 0);
  const int mine = succeeded;
  check(MPI_Allgather(&mine, 1, MPI_INT, all.data(), 1, MPI_INT, m_comm), "MPI_Allgather");
  m_writer_succeeded = all[0] != 0;
  return std::all_of(all.begin(), all.end(), [](int ok) { return ok != 0; });
}

void MpiFrameSplit::begin_pass(std::size_t tiles) {
  m_rendering = true;
  if (m_order.size() != tiles) {  // the first pass: by the predicted costs, or in tile order
    m_order = costliest_first(m_predicted, tiles);
    if (m_predicted.size() == tiles) m_first_pass_costs = m_predicted;
    m_tile_seconds.assign(tiles, 0.0);
    m_tile_seconds_sum.assign(m_rank == 0 ? tiles : 0, 0.0);
  }
  m_tiles = tiles;
  m_next = 0;
  m_exhausted = false;
  m_asked = false;
  m_mine.clear();
  m_pass_start = std::chrono::steady_clock::now();
  if (m_rank == 0 && m_ranks > 1) m_coordinator = std::thread([this] { coordinate(); });
}

void MpiFrameSplit::coordinate() {
  int done = 0;
  std::chrono::microseconds nap = kFirstNap;
  while (done < m_ranks - 1) {
    // Polled with naps between looks: Open MPI's blocking receive spins,
    // and took a core from rank 0's render threads (Sponza at 512², one
    // thread a rank: rank 0 rendered 326 of 1024 tiles, 1 -> 2 ranks 1.40x;
    // with 50 us naps, 451 and 1.65x). The naps grow while no request
    // comes; the other ranks ask for their next tile while they render one
    // (next_tile), so the wait hides behind their work.
    int waiting = 0;
    MPI_Status status;
    check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, m_comm, &waiting, &status), "MPI_Iprobe");
    if (!waiting) {
      std::this_thread::sleep_for(nap);
      nap = std::min(nap * 2, std::chrono::microseconds(kLongestNap));
      continue;
    }
    nap = kFirstNap;
    long long message = 0;
    check(MPI_Recv(&message, 1, MPI_LONG_LONG, status.MPI_SOURCE, status.MPI_TAG, m_comm, MPI_STATUS_IGNORE), "MPI_Recv");
    if (status.MPI_TAG == kTagDone) {
      ++done;
      continue;
    }
    const std::size_t next = m_next.fetch_add(1);
    const long long answer = next < m_tiles ? (long long)m_order[next] : -1;
    MPI_Send(&answer, 1, MPI_LONG_LONG, status.MPI_SOURCE, kTagTile, m_comm);
  }
}

void MpiFrameSplit::TileClock::start(const MpiFrameSplit* split, std::size_t tile) {
  owner = split;
  current = tile;
  began = std::chrono::steady_clock::now();
}

thread_local MpiFrameSplit::TileClock MpiFrameSplit::t_clock;

std::optional<std::size_t> MpiFrameSplit::next_tile() {
  // The calling thread's last tile is done: its seconds order the next pass.
  if (t_clock.owner == this) {
    m_tile_seconds[t_clock.current] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_clock.began).count();
    t_clock.owner = nullptr;
  }
  const auto handed = [&](std::size_t tile) {
    m_mine.push_back(tile);  // under m_mutex
    t_clock.start(this, tile);
    return tile;
  };
  if (m_rank == 0) {
    const std::size_t next = m_next.fetch_add(1);
    if (next >= m_tiles) return std::nullopt;
    const std::lock_guard<std::mutex> lock(m_mutex);
    return handed(m_order[next]);
  }
  // One request in flight per rank, its threads taking turns: the answer to
  // the last one, asked for when the last tile was handed out, is this
  // tile; then the next is asked for, to arrive while this one renders.
  const std::lock_guard<std::mutex> lock(m_mutex);
  if (m_exhausted) return std::nullopt;
  const long long request = 0;
  if (!m_asked) {
    check(MPI_Send(&request, 1, MPI_LONG_LONG, 0, kTagRequest, m_comm), "MPI_Send");
    check(MPI_Irecv(&m_answer, 1, MPI_LONG_LONG, 0, kTagTile, m_comm, &m_answer_request), "MPI_Irecv");
  }
  check(MPI_Wait(&m_answer_request, MPI_STATUS_IGNORE), "MPI_Wait");
  m_asked = false;
  if (m_answer < 0) {
    m_exhausted = true;
    return std::nullopt;
  }
  const std::size_t tile = std::size_t(m_answer);
  check(MPI_Send(&request, 1, MPI_LONG_LONG, 0, kTagRequest, m_comm), "MPI_Send");
  check(MPI_Irecv(&m_answer, 1, MPI_LONG_LONG, 0, kTagTile, m_comm, &m_answer_request), "MPI_Irecv");
  m_asked = true;
  return handed(tile);
}

void MpiFrameSplit::end_pass(Film* film, std::span<double> tile_estimates, std::span<std::uint64_t> counts) {
  // The rank's own time, before it waits for the others.
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_pass_start).count();
  if (m_rank != 0) {
    const long long done = 0;
    check(MPI_Send(&done, 1, MPI_LONG_LONG, 0, kTagDone, m_comm), "MPI_Send");
  } else if (m_coordinator.joinable()) {
    m_coordinator.join();
  }
  // Every rank's tiles, their seconds and estimates, then their pixels
  // (every channel, tile by tile), to rank 0; counts summed there (64-bit).
  std::vector<long long> my_tiles(m_mine.begin(), m_mine.end());
  std::vector<double> my_seconds, my_estimates;
  for (std::size_t tile : m_mine) {
    my_seconds.push_back(m_tile_seconds[tile]);
    my_estimates.push_back(tile < tile_estimates.size() ? tile_estimates[tile] : 0.0);
  }
  const int my_count = int(my_tiles.size());
  const std::size_t ranks = std::size_t(m_ranks);
  std::vector<int> tile_counts(ranks), tile_offsets(ranks);
  check(MPI_Gather(&my_count, 1, MPI_INT, tile_counts.data(), 1, MPI_INT, 0, m_comm), "MPI_Gather");
  int total = 0;
  for (int r = 0; r < m_ranks; ++r) tile_offsets[std::size_t(r)] = total, total += tile_counts[std::size_t(r)];
  std::vector<long long> all_tiles(std::size_t(std::max(total, 1)));
  std::vector<double> all_seconds(all_tiles.size()), all_estimates(all_tiles.size());
  check(MPI_Gatherv(my_tiles.data(), my_count, MPI_LONG_LONG, all_tiles.data(), tile_counts.data(), tile_offsets.data(),
                    MPI_LONG_LONG, 0, m_comm),
        "MPI_Gatherv");
  check(MPI_Gatherv(my_seconds.data(), my_count, MPI_DOUBLE, all_seconds.data(), tile_counts.data(), tile_offsets.data(),
                    MPI_DOUBLE, 0, m_comm),
        "MPI_Gatherv");
  check(MPI_Gatherv(my_estimates.data(), my_count, MPI_DOUBLE, all_estimates.data(), tile_counts.data(),
                    tile_offsets.data(), MPI_DOUBLE, 0, m_comm),
        "MPI_Gatherv");
  if (film) gather_pixels(*film);
  gather_shares(counts.empty() ? 0 : counts[0], seconds);
  std::vector<std::uint64_t> summed(counts.size(), 0);
  check(MPI_Reduce(counts.data(), summed.data(), int(counts.size()), MPI_UINT64_T, MPI_SUM, 0, m_comm), "MPI_Reduce");
  if (m_rank != 0) return;
  std::copy(summed.begin(), summed.end(), counts.begin());
  for (int k = 0; k < total; ++k) {
    const std::size_t tile = std::size_t(all_tiles[std::size_t(k)]);
    if (tile < tile_estimates.size()) tile_estimates[tile] = all_estimates[std::size_t(k)];
    if (tile < m_tile_seconds.size()) {
      m_tile_seconds[tile] = all_seconds[std::size_t(k)];
      m_tile_seconds_sum[tile] += all_seconds[std::size_t(k)];
    }
  }
  // The next pass's tiles, the slowest of this one first (ties in tile
  // order): the last tiles handed out are then the quickest, and no rank is
  // left with a long one while the others wait.
  m_order = costliest_first(m_tile_seconds, m_tiles);
}

void MpiFrameSplit::gather_pixels(Film& film) {
  // The other ranks' tiles' pixels, every channel, in the order of their
  // tiles; rank 0 has its own. Counted in pixels (PixelType).
  const auto film_channels = channels(film);
  std::size_t floats_per_pixel = 0;
  for (const auto& [v, n] : film_channels) floats_per_pixel += std::size_t(n);
  const PixelType pixel_type(floats_per_pixel * sizeof(float));
  std::vector<float> my_pixels;
  if (m_rank != 0)
    for (std::size_t tile : m_mine)
      for_each_pixel(film.width, film.height, tile, [&](std::size_t p) {
        for (const auto& [v, n] : film_channels)
          for (int c = 0; c < n; ++c) my_pixels.push_back((*v)[p * std::size_t(n) + std::size_t(c)]);
      });
  const std::size_t ranks = std::size_t(m_ranks);
  const int my_count = int(my_pixels.size() / floats_per_pixel);
  std::vector<int> counts(ranks), offsets(ranks);
  check(MPI_Gather(&my_count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, m_comm), "MPI_Gather");
  long long total = 0;
  for (std::size_t r = 0; r < ranks; ++r) offsets[r] = int(total), total += counts[r];
  std::vector<float> all_pixels(std::size_t(std::max<long long>(total, 1)) * floats_per_pixel);
  std::vector<long long> tiles(m_mine.begin(), m_mine.end());
  const int my_tiles = m_rank == 0 ? 0 : int(tiles.size());
  std::vector<int> tile_counts(ranks), tile_offsets(ranks);
  check(MPI_Gather(&my_tiles, 1, MPI_INT, tile_counts.data(), 1, MPI_INT, 0, m_comm), "MPI_Gather");
  int tile_total = 0;
  for (std::size_t r = 0; r < ranks; ++r) tile_offsets[r] = tile_total, tile_total += tile_counts[r];
  std::vector<long long> all_tiles(std::size_t(std::max(tile_total, 1)));
  check(MPI_Gatherv(tiles.data(), my_tiles, MPI_LONG_LONG, all_tiles.data(), tile_counts.data(), tile_offsets.data(),
                    MPI_LONG_LONG, 0, m_comm),
        "MPI_Gatherv");
  check(MPI_Gatherv(my_pixels.data(), my_count, pixel_type, all_pixels.data(), counts.data(), offsets.data(), pixel_type,
                    0, m_comm),
        "MPI_Gatherv");
  if (m_rank != 0) return;
  std::size_t at = 0;
  for (int k = 0; k < tile_total; ++k)
    for_each_pixel(film.width, film.height, std::size_t(all_tiles[std::size_t(k)]), [&](std::size_t p) {
      for (const auto& [v, n] : film_channels)
        for (int c = 0; c < n; ++c) (*v)[p * std::size_t(n) + std::size_t(c)] = all_pixels[at++];
    });
  KAPPA_CHECK_EQ(at, std::size_t(total) * floats_per_pixel);
}

void MpiFrameSplit::share_pass_state(int width, int height, std::size_t bytes,
                                     const std::function<void(std::size_t, std::byte*)>& pack,
                                     const std::function<void(std::size_t, const std::byte*)>& unpack) {
  // Every rank's tiles of the pass and their pixels' state, to every rank.
  const PixelType pixel_type(bytes);
  std::vector<long long> tiles(m_mine.begin(), m_mine.end());
  std::vector<std::byte> mine;
  for (std::size_t tile : m_mine)
    for_each_pixel(width, height, tile, [&](std::size_t p) {
      mine.resize(mine.size() + bytes);
      pack(p, mine.data() + mine.size() - bytes);
    });
  const std::size_t ranks = std::size_t(m_ranks);
  const int my_tiles = int(tiles.size()), my_pixels = int(mine.size() / bytes);
  std::vector<int> tile_counts(ranks), tile_offsets(ranks), pixel_counts(ranks), pixel_offsets(ranks);
  check(MPI_Allgather(&my_tiles, 1, MPI_INT, tile_counts.data(), 1, MPI_INT, m_comm), "MPI_Allgather");
  check(MPI_Allgather(&my_pixels, 1, MPI_INT, pixel_counts.data(), 1, MPI_INT, m_comm), "MPI_Allgather");
  int tile_total = 0;
  long long pixel_total = 0;
  for (std::size_t r = 0; r < ranks; ++r) {
    tile_offsets[r] = tile_total, tile_total += tile_counts[r];
    pixel_offsets[r] = int(pixel_total), pixel_total += pixel_counts[r];
  }
  std::vector<long long> all_tiles(std::size_t(std::max(tile_total, 1)));
  std::vector<std::byte> all(std::size_t(std::max<long long>(pixel_total, 1)) * bytes);
  check(MPI_Allgatherv(tiles.data(), my_tiles, MPI_LONG_LONG, all_tiles.data(), tile_counts.data(), tile_offsets.data(),
                       MPI_LONG_LONG, m_comm),
        "MPI_Allgatherv");
  check(MPI_Allgatherv(mine.data(), my_pixels, pixel_type, all.data(), pixel_counts.data(), pixel_offsets.data(),
                       pixel_type, m_comm),
        "MPI_Allgatherv");
  // Each rank's own tiles are as they were; the others' are copied in.
  std::size_t at = 0;
  for (std::size_t r = 0; r < ranks; ++r)
    for (int k = tile_offsets[r]; k < tile_offsets[r] + tile_counts[r]; ++k)
      for_each_pixel(width, height, std::size_t(all_tiles[std::size_t(k)]), [&](std::size_t p) {
        if (int(r) != m_rank) unpack(p, all.data() + at);
        at += bytes;
      });
  KAPPA_CHECK_EQ(at, std::size_t(pixel_total) * bytes);
}

void MpiFrameSplit::gather_shares(std::uint64_t rays, double seconds) {
  // Fixed-size records: the host's name padded to MPI_MAX_PROCESSOR_NAME.
  struct Record {
    std::uint64_t tiles, rays, threads;
    double seconds;
    char host[MPI_MAX_PROCESSOR_NAME];
  };
  Record mine{m_mine.size(), rays, std::uint64_t(active_threads()), seconds, {}};
  std::memcpy(mine.host, m_host.data(), std::min(m_host.size(), sizeof mine.host - 1));
  std::vector<Record> all(m_rank == 0 ? std::size_t(m_ranks) : 0);
  check(MPI_Gather(&mine, int(sizeof mine), MPI_BYTE, all.data(), int(sizeof mine), MPI_BYTE, 0, m_comm), "MPI_Gather");
  if (m_rank != 0) return;
  m_shares.resize(std::size_t(m_ranks));
  for (int r = 0; r < m_ranks; ++r) {
    ProcessShare& share = m_shares[std::size_t(r)];
    const Record& record = all[std::size_t(r)];
    share.process = r;
    share.host = std::string(record.host, strnlen(record.host, sizeof record.host));
    share.threads = int(record.threads);
    share.tiles += record.tiles;
    share.rays = record.rays;  // the rank's counts so far, all passes
    share.time_s += record.seconds;
  }
}

std::uint64_t MpiFrameSplit::writer_value(std::uint64_t value) {
  check(MPI_Bcast(&value, 1, MPI_UINT64_T, 0, m_comm), "MPI_Bcast");
  return value;
}

std::string MpiFrameSplit::writer_text(const std::string& text) {
  std::string out = text;
  out.resize(std::size_t(writer_value(text.size())));
  // In pieces of at most 2^30 bytes: MPI counts are ints (a checkpoint of a
  // large frame is gigabytes).
  constexpr std::size_t kPiece = std::size_t(1) << 30;
  for (std::size_t at = 0; at < out.size(); at += kPiece)
    check(MPI_Bcast(out.data() + at, int(std::min(kPiece, out.size() - at)), MPI_CHAR, 0, m_comm), "MPI_Bcast");
  return out;
}

void MpiFrameSplit::sum_on_writer(std::span<std::uint64_t> values) {
  // In pieces of at most 2^30 values: MPI counts are ints.
  constexpr std::size_t kPiece = std::size_t(1) << 30;
  for (std::size_t at = 0; at < values.size(); at += kPiece) {
    const int n = int(std::min(kPiece, values.size() - at));
    if (m_rank == 0)
      check(MPI_Reduce(MPI_IN_PLACE, values.data() + at, n, MPI_UINT64_T, MPI_SUM, 0, m_comm), "MPI_Reduce");
    else
      check(MPI_Reduce(values.data() + at, nullptr, n, MPI_UINT64_T, MPI_SUM, 0, m_comm), "MPI_Reduce");
  }
}

}  // namespace kappa
