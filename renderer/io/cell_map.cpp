#include "renderer/io/cell_map.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/error.h"
#include "renderer/io/atomic_file.h"
#include "renderer/io/exr_output.h"
#include "renderer/io/png_output.h"

namespace kappa {

void write_cell_map(AtomicOutput& out, const CellLayout& cells, const RenderCounters& counters, int axis) {
  const std::filesystem::path& file = out.target();
  std::string ext = file.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".exr" && ext != ".png") fail(file, 0, "--cell-map: the file must end in .exr or .png");
  if (!counters.classes[0].per_cell()) fail(file, 0, "--cell-map: per-cell statistics were refused for this frame");

  const int u_axis = axis == 0 ? 1 : 0, v_axis = axis == 2 ? 1 : 2;  // image x and y
  const std::uint64_t n = cells.cell_count();
  // Pixels of the smallest cell's size over the box the cells tile.
  const CellBox bounds = cells.bounds();
  double pixel_u = INFINITY, pixel_v = INFINITY;
  for (std::uint64_t i = 0; i < n; ++i) {
    const CellBox b = cells.cell_box(i);
    pixel_u = std::min(pixel_u, b.hi[u_axis] - b.lo[u_axis]);
    pixel_v = std::min(pixel_v, b.hi[v_axis] - b.lo[v_axis]);
  }
  const auto pixel_of = [](double x, double lo, double size) { return std::llround((x - lo) / size); };
  const int w = int(std::max<long long>(1, pixel_of(bounds.hi[u_axis], bounds.lo[u_axis], pixel_u)));
  const int h = int(std::max<long long>(1, pixel_of(bounds.hi[v_axis], bounds.lo[v_axis], pixel_v)));
  // p_i over the rays counted per cell (every ray, or those of the sampled paths).
  std::uint64_t rays = 0;
  for (const CellCounters& c : counters.classes) rays += c.per_cell_queries();
  const std::vector<std::uint32_t> theta_i = cells.occupancies();
  std::vector<double> p(std::size_t(w) * std::size_t(h)), theta(p.size());
  for (std::uint64_t i = 0; i < n; ++i) {  // in index order: each pixel sums its cells in a fixed order
    std::uint64_t visits = 0;
    for (const CellCounters& cls : counters.classes) visits += cls.visits_at(i);
    const CellBox b = cells.cell_box(i);
    const long long u0 = std::clamp<long long>(pixel_of(b.lo[u_axis], bounds.lo[u_axis], pixel_u), 0, w - 1);
    const long long u1 = std::clamp<long long>(pixel_of(b.hi[u_axis], bounds.lo[u_axis], pixel_u), u0 + 1, w);
    const long long v0 = std::clamp<long long>(pixel_of(b.lo[v_axis], bounds.lo[v_axis], pixel_v), 0, h - 1);
    const long long v1 = std::clamp<long long>(pixel_of(b.hi[v_axis], bounds.lo[v_axis], pixel_v), v0 + 1, h);
    // A cell larger than a pixel (grid2's empty top cells) spreads its
    // values evenly over the pixels its box covers, so that the image's
    // sums stay p_tot and Theta_tot.
    const double share = 1.0 / double((u1 - u0) * (v1 - v0));
    for (long long v = v0; v < v1; ++v) {
      for (long long u = u0; u < u1; ++u) {
        // Image rows run top-down: the v axis points up in the picture.
        const std::size_t px = std::size_t(h - 1 - v) * std::size_t(w) + std::size_t(u);
        p[px] += (rays > 0 ? double(visits) / double(rays) : 0.0) * share;
        theta[px] += double(theta_i[i]) * share;
      }
    }
  }

  const Metadata axis_attribute = {{"kappa:projection_axis", std::string(1, "xyz"[axis])}};
  if (ext == ".exr") {
    std::vector<float> pixels;
    pixels.reserve(2 * p.size());
    for (std::size_t i = 0; i < p.size(); ++i) pixels.insert(pixels.end(), {float(p[i]), float(theta[i])});
    write_float_exr(out.temp_path(), w, h, {"p", "theta"}, pixels, axis_attribute, file);
  } else {
    // sqrt(p_i / max p) in red, sqrt(Theta_i / max Theta) in green, 8 bits.
    const double max_p = std::max(1e-300, *std::max_element(p.begin(), p.end()));
    const double max_t = std::max(1e-300, *std::max_element(theta.begin(), theta.end()));
    const auto byte = [](double x) { return std::uint8_t(std::lround(std::clamp(x, 0.0, 1.0) * 255.0)); };
    std::vector<std::uint8_t> pixels;
    pixels.reserve(3 * p.size());
    for (std::size_t i = 0; i < p.size(); ++i)
      pixels.insert(pixels.end(), {byte(std::sqrt(p[i] / max_p)), byte(std::sqrt(theta[i] / max_t)), 0});
    write_png(out.temp_path(), w, h, pixels, file);
  }
  out.commit();
}

}  // namespace kappa
