#include "renderer/io/checkpoint_file.h"

#include <cstring>
#include <type_traits>

#include "core/hash.h"
#include "core/input_error.h"
#include "renderer/version.h"

namespace kappa {
namespace {

constexpr std::string_view kMagic = "kappa checkpoint 1\n";

template <class T>
void append(std::string& out, const std::vector<T>& values) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (!values.empty()) out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

template <class T>
std::vector<T> take(std::string_view& in, std::size_t count, const std::string& file) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (count > in.size() / sizeof(T)) throw InputError(file + ": a damaged checkpoint (cut short)");
  std::vector<T> values(count);
  if (count > 0) std::memcpy(values.data(), in.data(), count * sizeof(T));  // an empty vector's data() may be null
  in.remove_prefix(count * sizeof(T));
  return values;
}

std::string hash_text(std::uint64_t h) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

}  // namespace

std::filesystem::path checkpoint_path(const std::filesystem::path& image) {
  return std::filesystem::path(image.string() + ".checkpoint");
}

std::string encode_checkpoint(const nlohmann::ordered_json& settings, const FrameProgress& p) {
  const nlohmann::ordered_json head = {{"kappa_version", version_string()},
                                       {"settings", settings},
                                       {"passes", p.passes},
                                       {"spp", p.spp},
                                       {"rays", p.rays},
                                       {"nonfinite", p.nonfinite},
                                       {"elapsed_s", p.elapsed_s},
                                       {"cell_sample", p.cell_sample},
                                       {"pixels", p.samples.size()},
                                       {"aov_pixels", p.aovs.size()},
                                       {"active", p.active.size()},
                                       {"counters", p.counters.size()},
                                       {"pixel_bytes", sizeof(PixelSamples)},
                                       {"aov_bytes", sizeof(PixelAovSums)}};
  std::string out(kMagic);
  out += head.dump() + "\n";
  append(out, p.samples);
  append(out, p.aovs);
  append(out, p.active);
  append(out, p.counters);
  out += hash_text(fnv1a64(out)) + "\n";
  return out;
}

FrameProgress decode_checkpoint(const std::string& bytes, const std::string& file,
                                const nlohmann::ordered_json& settings, std::size_t pixels, bool aovs) {
  std::string_view in(bytes);
  if (in.substr(0, kMagic.size()) != kMagic) throw InputError(file + ": not a Kappa checkpoint");
  // The hash first: a checkpoint cut short or changed says so, not what it
  // would then misread.
  constexpr std::size_t kHashLine = 17;
  if (in.size() < kMagic.size() + kHashLine ||
      hash_text(fnv1a64(in.substr(0, in.size() - kHashLine))) + "\n" != in.substr(in.size() - kHashLine))
    throw InputError(file + ": a damaged checkpoint (its hash does not match its bytes)");
  in = in.substr(kMagic.size(), in.size() - kMagic.size() - kHashLine);
  const std::size_t eol = in.find('\n');
  nlohmann::ordered_json head;
  try {
    head = nlohmann::ordered_json::parse(in.substr(0, eol));
  } catch (const nlohmann::json::exception&) {
    throw InputError(file + ": a damaged checkpoint (its header is not JSON)");
  }
  in.remove_prefix(eol + 1);
  try {
    const std::string version = head.at("kappa_version").get<std::string>();
    if (version != version_string())
      throw InputError(file + ": a checkpoint of Kappa " + version + ", not of this Kappa (" + version_string() +
                       "): render again without --resume");
    const nlohmann::ordered_json& saved = head.at("settings");
    for (const auto& [key, value] : settings.items())
      if (!saved.contains(key) || saved[key] != value)
        throw InputError(file + ": a checkpoint of another render: its " + key + " is " +
                         (saved.contains(key) ? saved[key].dump() : std::string("not set")) + ", here " + value.dump());
    for (const auto& [key, value] : saved.items())
      if (!settings.contains(key))
        throw InputError(file + ": a checkpoint of another render: its " + key + " is " + value.dump() + ", here not set");
    if (head.at("pixel_bytes").get<std::size_t>() != sizeof(PixelSamples) ||
        head.at("aov_bytes").get<std::size_t>() != sizeof(PixelAovSums) ||
        head.at("pixels").get<std::size_t>() != pixels ||
        head.at("aov_pixels").get<std::size_t>() != (aovs ? pixels : 0))
      throw InputError(file + ": a checkpoint of another frame (its pixels' sums do not fit this one's)");
    FrameProgress p;
    p.passes = head.at("passes").get<int>();
    p.spp = head.at("spp").get<int>();
    p.rays = head.at("rays").get<std::uint64_t>();
    p.nonfinite = head.at("nonfinite").get<std::uint64_t>();
    p.elapsed_s = head.at("elapsed_s").get<double>();
    p.cell_sample = head.at("cell_sample").get<std::uint64_t>();
    p.samples = take<PixelSamples>(in, pixels, file);
    p.aovs = take<PixelAovSums>(in, aovs ? pixels : 0, file);
    const std::size_t active = head.at("active").get<std::size_t>();
    if (active != 0 && active != pixels) throw InputError(file + ": a damaged checkpoint (its retired pixels)");
    p.active = take<std::uint8_t>(in, active, file);
    p.counters = take<std::uint64_t>(in, head.at("counters").get<std::size_t>(), file);
    if (!in.empty()) throw InputError(file + ": a damaged checkpoint (bytes after its arrays)");
    if (p.passes < 1 || p.spp < 1) throw InputError(file + ": a damaged checkpoint (no pass)");
    return p;
  } catch (const nlohmann::json::exception&) {
    throw InputError(file + ": a damaged checkpoint (its header lacks a value)");
  }
}

}  // namespace kappa
