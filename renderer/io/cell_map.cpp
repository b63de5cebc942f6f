#include "renderer/io/cell_map.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "renderer/io/atomic_file.h"
#include "renderer/util/error.h"

namespace kappa {

void write_cell_map(AtomicOutput& out, const UniformGrid& grid, const RenderCounters& counters, int axis) {
  const std::filesystem::path& file = out.target();
  std::string ext = file.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".exr" && ext != ".png") fail(file, 0, "--cell-map: the file must end in .exr or .png");
  if (!counters.classes[0].per_cell()) fail(file, 0, "--cell-map: per-cell statistics were refused for this frame");

  const GridResolution& r = grid.info().resolution;
  const int u_axis = axis == 0 ? 1 : 0, v_axis = axis == 2 ? 1 : 2;  // image x and y
  const int w = r[u_axis], h = r[v_axis], depth = r[axis];
  // p_i over the rays counted per cell (every ray, or those of the sampled paths).
  std::uint64_t rays = 0;
  for (const CellCounters& c : counters.classes) rays += c.per_cell_queries();
  std::vector<double> p(std::size_t(w) * std::size_t(h)), theta(p.size());
  std::vector<std::uint64_t> all_visits(r.cells(), 0);
  for (const CellCounters& cls : counters.classes)
    for (std::size_t i = 0; i < all_visits.size(); ++i) all_visits[i] += cls.visits_at(i);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      for (int k = 0; k < depth; ++k) {
        int ijk[3];
        ijk[u_axis] = u, ijk[v_axis] = v, ijk[axis] = k;
        const std::uint64_t c = grid.cell_index(ijk[0], ijk[1], ijk[2]);
        const std::uint64_t visits = all_visits[c];
        // Image rows run top-down: the v axis points up in the picture.
        const std::size_t px = std::size_t(h - 1 - v) * std::size_t(w) + std::size_t(u);
        p[px] += rays > 0 ? double(visits) / double(rays) : 0.0;
        theta[px] += double(grid.cell(c).size());
      }
    }
  }

  std::vector<float> pixels;
  int channels = 0;
  OIIO::ImageSpec spec;
  if (ext == ".exr") {
    channels = 2;
    for (std::size_t i = 0; i < p.size(); ++i) pixels.insert(pixels.end(), {float(p[i]), float(theta[i])});
    spec = OIIO::ImageSpec(w, h, channels, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"p", "theta"};
  } else {
    channels = 3;
    const double max_p = std::max(1e-300, *std::max_element(p.begin(), p.end()));
    const double max_t = std::max(1e-300, *std::max_element(theta.begin(), theta.end()));
    for (std::size_t i = 0; i < p.size(); ++i)
      pixels.insert(pixels.end(), {float(std::sqrt(p[i] / max_p)), float(std::sqrt(theta[i] / max_t)), 0.0f});
    spec = OIIO::ImageSpec(w, h, channels, OIIO::TypeDesc::UINT8);
  }
  spec.attribute("kappa:projection_axis", std::string(1, "xyz"[axis]));
  auto img = OIIO::ImageOutput::create(ext == ".exr" ? "openexr" : "png");
  if (!img || !img->open(out.temp_path().string(), spec) ||
      !img->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) || !img->close())
    fail(file, 0, "cannot write the cell map: " + (img ? img->geterror() : OIIO::geterror()));
  out.commit();
}

}  // namespace kappa
