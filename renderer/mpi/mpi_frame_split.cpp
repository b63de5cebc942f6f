#include "renderer/mpi/mpi_frame_split.h"

#include <algorithm>
#include <cstring>

#include "core/check.h"
#include "renderer/render/film.h"

namespace kappa {
namespace {

constexpr int kTagRequest = 1;  // a rank asks for a tile
constexpr int kTagTile = 2;     // rank 0's answer: a tile, or -1 for none left
constexpr int kTagDone = 3;     // a rank has rendered all its tiles of the pass

/// The film's channels, in one order every rank uses, with their components.
std::vector<std::pair<std::vector<float>*, int>> channels(Film& film) {
  std::vector<std::pair<std::vector<float>*, int>> c = {{&film.rgb, 3}};
  for (auto [v, n] : {std::pair{&film.albedo, 3}, {&film.normal, 3}, {&film.depth, 1}, {&film.cost_cells, 1},
                      {&film.cost_tests, 1}, {&film.variance, 3}, {&film.spp, 1}})
    if (!v->empty()) c.emplace_back(v, n);
  return c;
}

/// Calls `fn(pixel)` for every pixel of `tile`, row by row.
template <class Fn>
void for_each_pixel(const Film& film, std::size_t tile, Fn&& fn) {
  const int tiles_x = (film.width + kTileSize - 1) / kTileSize;
  const int x0 = int(tile % std::size_t(tiles_x)) * kTileSize, y0 = int(tile / std::size_t(tiles_x)) * kTileSize;
  for (int y = y0; y < std::min(y0 + kTileSize, film.height); ++y)
    for (int x = x0; x < std::min(x0 + kTileSize, film.width); ++x)
      fn(std::size_t(y) * std::size_t(film.width) + std::size_t(x));
}

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

}  // namespace

MpiFrameSplit::MpiFrameSplit(MPI_Comm comm) {
  check(MPI_Comm_dup(comm, &m_comm), "MPI_Comm_dup");
  MPI_Comm_rank(m_comm, &m_rank);
  MPI_Comm_size(m_comm, &m_ranks);
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
  m_tiles = tiles;
  m_next = 0;
  m_exhausted = false;
  m_mine.clear();
  if (m_rank == 0 && m_ranks > 1) m_coordinator = std::thread([this] { coordinate(); });
}

void MpiFrameSplit::coordinate() {
  int done = 0;
  while (done < m_ranks - 1) {
    long long message = 0;
    MPI_Status status;
    MPI_Recv(&message, 1, MPI_LONG_LONG, MPI_ANY_SOURCE, MPI_ANY_TAG, m_comm, &status);
    if (status.MPI_TAG == kTagDone) {
      ++done;
      continue;
    }
    const std::size_t tile = m_next.fetch_add(1);
    const long long answer = tile < m_tiles ? (long long)tile : -1;
    MPI_Send(&answer, 1, MPI_LONG_LONG, status.MPI_SOURCE, kTagTile, m_comm);
  }
}

std::optional<std::size_t> MpiFrameSplit::next_tile() {
  if (m_rank == 0) {
    const std::size_t tile = m_next.fetch_add(1);
    if (tile >= m_tiles) return std::nullopt;
    const std::lock_guard<std::mutex> lock(m_mutex);
    m_mine.push_back(tile);
    return tile;
  }
  // One request in flight per rank: its threads take turns asking.
  const std::lock_guard<std::mutex> lock(m_mutex);
  if (m_exhausted) return std::nullopt;
  const long long request = 0;
  long long answer = -1;
  check(MPI_Send(&request, 1, MPI_LONG_LONG, 0, kTagRequest, m_comm), "MPI_Send");
  check(MPI_Recv(&answer, 1, MPI_LONG_LONG, 0, kTagTile, m_comm, MPI_STATUS_IGNORE), "MPI_Recv");
  if (answer < 0) {
    m_exhausted = true;
    return std::nullopt;
  }
  m_mine.push_back(std::size_t(answer));
  return std::size_t(answer);
}

void MpiFrameSplit::end_pass(Film& film, std::span<double> tile_estimates, std::span<std::uint64_t> counts) {
  if (m_rank != 0) {
    const long long done = 0;
    check(MPI_Send(&done, 1, MPI_LONG_LONG, 0, kTagDone, m_comm), "MPI_Send");
  } else if (m_coordinator.joinable()) {
    m_coordinator.join();
  }
  // Every rank's tiles, then their pixels (every channel, tile by tile) and
  // estimates, to rank 0; counts summed there (64-bit).
  const auto film_channels = channels(film);
  std::vector<long long> my_tiles(m_mine.begin(), m_mine.end());
  std::vector<float> my_pixels;
  std::vector<double> my_estimates;
  if (m_rank != 0) {
    for (std::size_t tile : m_mine) {
      for_each_pixel(film, tile, [&](std::size_t p) {
        for (const auto& [v, n] : film_channels)
          for (int c = 0; c < n; ++c) my_pixels.push_back((*v)[p * std::size_t(n) + std::size_t(c)]);
      });
      my_estimates.push_back(tile < tile_estimates.size() ? tile_estimates[tile] : 0.0);
    }
  }
  const int my_count = m_rank == 0 ? 0 : int(my_tiles.size());
  const std::size_t ranks = std::size_t(m_ranks);
  std::vector<int> tile_counts(ranks), tile_offsets(ranks);
  check(MPI_Gather(&my_count, 1, MPI_INT, tile_counts.data(), 1, MPI_INT, 0, m_comm), "MPI_Gather");
  int total = 0;
  for (int r = 0; r < m_ranks; ++r) tile_offsets[std::size_t(r)] = total, total += tile_counts[std::size_t(r)];
  std::vector<long long> all_tiles(std::size_t(std::max(total, 1)));
  std::vector<double> all_estimates(std::size_t(std::max(total, 1)));
  check(MPI_Gatherv(my_tiles.data(), my_count, MPI_LONG_LONG, all_tiles.data(), tile_counts.data(), tile_offsets.data(),
                    MPI_LONG_LONG, 0, m_comm),
        "MPI_Gatherv");
  check(MPI_Gatherv(my_estimates.data(), my_count, MPI_DOUBLE, all_estimates.data(), tile_counts.data(),
                    tile_offsets.data(), MPI_DOUBLE, 0, m_comm),
        "MPI_Gatherv");
  // Pixel counts per rank, from the tiles' sizes (edge tiles are smaller).
  std::vector<int> float_counts(ranks), float_offsets(ranks);
  const int my_floats = int(my_pixels.size());
  check(MPI_Gather(&my_floats, 1, MPI_INT, float_counts.data(), 1, MPI_INT, 0, m_comm), "MPI_Gather");
  long long float_total = 0;
  for (int r = 0; r < m_ranks; ++r) float_offsets[std::size_t(r)] = int(float_total), float_total += float_counts[std::size_t(r)];
  std::vector<float> all_pixels(std::size_t(std::max<long long>(float_total, 1)));
  check(MPI_Gatherv(my_pixels.data(), my_floats, MPI_FLOAT, all_pixels.data(), float_counts.data(),
                    float_offsets.data(), MPI_FLOAT, 0, m_comm),
        "MPI_Gatherv");
  std::vector<std::uint64_t> summed(counts.size(), 0);
  check(MPI_Reduce(counts.data(), summed.data(), int(counts.size()), MPI_UINT64_T, MPI_SUM, 0, m_comm), "MPI_Reduce");
  if (m_rank != 0) return;
  std::copy(summed.begin(), summed.end(), counts.begin());
  std::size_t at = 0;
  for (int k = 0; k < total; ++k) {
    const std::size_t tile = std::size_t(all_tiles[std::size_t(k)]);
    for_each_pixel(film, tile, [&](std::size_t p) {
      for (const auto& [v, n] : film_channels)
        for (int c = 0; c < n; ++c) (*v)[p * std::size_t(n) + std::size_t(c)] = all_pixels[at++];
    });
    if (tile < tile_estimates.size()) tile_estimates[tile] = all_estimates[std::size_t(k)];
  }
  KAPPA_CHECK_EQ(at, std::size_t(float_total));
}

std::uint64_t MpiFrameSplit::writer_value(std::uint64_t value) {
  check(MPI_Bcast(&value, 1, MPI_UINT64_T, 0, m_comm), "MPI_Bcast");
  return value;
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
