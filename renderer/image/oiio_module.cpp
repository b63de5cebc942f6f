// The OpenImageIO module (libkappa_oiio.so): ImageLibrary on OpenImageIO's
// TextureSystem, ImageInput and ImageOutput. Built as a module of its own and
// loaded by image_library() on first use, so that only a run that reads a
// texture, an environment image or writes a preview loads OpenImageIO.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "renderer/image/image_library.h"

namespace kappa {
namespace {

namespace OIIO = OIIO_NAMESPACE;

/// Standard error sent to /dev/null while a file is read at load: libpng
/// (under OpenImageIO) prints its own "libpng error: ..." lines, and a
/// refusal is one line, Kappa's, with OpenImageIO's words in it.
class StderrMuted {
 public:
  StderrMuted() : m_saved(::dup(2)) {
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (m_saved >= 0 && null >= 0) ::dup2(null, 2);
    if (null >= 0) ::close(null);
  }
  ~StderrMuted() {
    if (m_saved < 0) return;
    ::dup2(m_saved, 2);
    ::close(m_saved);
  }
  StderrMuted(const StderrMuted&) = delete;
  StderrMuted& operator=(const StderrMuted&) = delete;

 private:
  int m_saved;
};

/// An image held in memory (add_memory_file): its bytes, and the reader the
/// texture cache reads them through (each whole-image read at load gets a
/// reader of its own, so that no two share a position).
struct MemoryFile {
  std::vector<unsigned char> bytes;
  std::unique_ptr<OIIO::Filesystem::IOMemReader> cache_reader;
};

/// An open image and the memory reader it reads from, if any (which must
/// outlive it).
struct OpenInput {
  std::unique_ptr<OIIO::Filesystem::IOMemReader> reader;
  std::unique_ptr<OIIO::ImageInput> in;
  OIIO::ImageInput* operator->() const { return in.get(); }
  explicit operator bool() const { return bool(in); }
};

/// The configuration every open uses: colour unassociated from alpha (as the
/// cache reads it), and the memory reader for an image held in memory.
OIIO::ImageSpec input_config(OIIO::Filesystem::IOProxy* reader) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  if (reader) {
    void* p = reader;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &p);
  }
  return config;
}

std::runtime_error failure(const std::string& what, const std::string& detail) {
  std::string d = detail;
  while (!d.empty() && (d.back() == '\n' || d.back() == ' ')) d.pop_back();
  if (const auto nl = d.find('\n'); nl != std::string::npos) d = d.substr(0, nl);  // one line
  return std::runtime_error(d.empty() ? what : what + ": " + d);
}

class OiioLibrary final : public ImageLibrary {
 public:
  explicit OiioLibrary(int cache_mb) : m_ts(OIIO::TextureSystem::create(/*shared=*/false)) {
    m_ts->attribute("max_memory_MB", float(cache_mb));
    // Untiled, un-MIP-mapped files (PNG, JPEG) are cached in 64-texel tiles
    // with MIP levels made in memory, as a renderer's lookups need.
    m_ts->attribute("autotile", 64);
    m_ts->attribute("automip", 1);
    m_ts->attribute("accept_untiled", 1);
    m_ts->attribute("accept_unmipped", 1);
    m_ts->attribute("max_open_files", 100);
    // Colour as the file stores it beside its alpha (straight, as Blender
    // reads a PNG), not premultiplied by it: a cut-out's edge keeps its colour.
    m_ts->attribute("unassociatedalpha", 1);
    m_cache_mb = cache_mb;
  }
  ~OiioLibrary() override { OIIO::TextureSystem::destroy(m_ts); }

  void add_memory_file(const std::string& name, std::vector<unsigned char> bytes) override {
    const std::lock_guard<std::mutex> lock(m_memory_mutex);
    if (m_memory.count(name)) return;
    auto file = std::make_unique<MemoryFile>();
    file->bytes = std::move(bytes);
    file->cache_reader = std::make_unique<OIIO::Filesystem::IOMemReader>(file->bytes.data(), file->bytes.size());
    m_memory.emplace(name, std::move(file));
  }

  ImageFacts inspect(const std::string& path) override {
    const StderrMuted muted;
    auto in = open_input(path);
    if (!in) throw failure("cannot read it as an image", OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    ImageFacts f;
    f.width = spec.width;
    f.height = spec.height;
    f.channels = spec.nchannels;
    f.alpha_channel = spec.alpha_channel;
    f.alpha = spec.alpha_channel >= 0;
    f.floating = spec.format.is_floating_point();
    f.format = in->format_name();
    return f;
  }

  std::vector<float> read(const std::string& path, int channels) override {
    const StderrMuted muted;
    auto in = open_input(path);
    if (!in) throw failure("cannot read it as an image", OIIO::geterror());
    const OIIO::ImageSpec spec = in->spec();
    const std::size_t texels = std::size_t(spec.width) * std::size_t(spec.height);
    std::vector<float> all(texels * std::size_t(spec.nchannels));
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data()))
      throw failure("cannot read its pixels", in->geterror());
    std::vector<float> out(texels * std::size_t(channels), 0.0f);
    for (std::size_t i = 0; i < texels; ++i)
      for (int c = 0; c < channels; ++c) {
        float v = 0.0f;
        if (c < spec.nchannels) v = all[i * spec.nchannels + c];
        else if (c == 3) v = 1.0f;  // an alpha the file does not have: opaque
        out[i * channels + c] = v;
      }
    return out;
  }

  TexelScan scan(const std::string& path) override {
    const StderrMuted muted;
    auto in = open_input(path);
    if (!in) throw failure("cannot read it as an image", OIIO::geterror());
    const OIIO::ImageSpec spec = in->spec();
    TexelScan s;
    auto count = [&](const std::vector<float>& texels) {
      for (float v : texels) {
        s.nan += std::isnan(v);
        s.infinite += std::isinf(v);
        s.negative += v < 0.0f;
      }
    };
    // Every texel is read, whatever the format: a truncated or corrupt file
    // fails here, at load, not as black texels in the render.
    if (spec.tile_width == 0) {
      const int rows = 64;
      std::vector<float> chunk(std::size_t(spec.width) * std::size_t(spec.nchannels) * rows);
      for (int y = spec.y; y < spec.y + spec.height; y += rows) {
        const int end = std::min(y + rows, spec.y + spec.height);
        chunk.resize(std::size_t(spec.width) * std::size_t(spec.nchannels) * std::size_t(end - y));
        if (!in->read_scanlines(0, 0, y, end, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, chunk.data()))
          throw failure("cannot read its pixels", in->geterror());
        count(chunk);
      }
    } else {
      std::vector<float> all(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(spec.nchannels));
      if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data()))
        throw failure("cannot read its pixels", in->geterror());
      count(all);
    }
    return s;
  }

  void* texture(const std::string& path) override {
    if (const MemoryFile* file = memory_file(path)) {
      // The cache opens it through its reader, the first time it is named.
      const OIIO::ImageSpec config = input_config(file->cache_reader.get());
      m_ts->imagecache()->add_file(OIIO::ustring(path), nullptr, &config);
    }
    return m_ts->get_texture_handle(OIIO::ustring(path));
  }

  bool lookup(void* texture, TextureWrap wrap_s, TextureWrap wrap_t, TextureFilter filter, int first, int count, const TextureCoords& at,
              float* out) override {
    thread_local OIIO::TextureSystem::Perthread* thread_info = nullptr;
    thread_local const OiioLibrary* thread_owner = nullptr;
    if (thread_owner != this) {
      thread_info = m_ts->get_perthread_info();
      thread_owner = this;
    }
    OIIO::TextureOpt opt;
    opt.firstchannel = first;
    opt.swrap = oiio_wrap(wrap_s);
    opt.twrap = oiio_wrap(wrap_t);
    if (filter == TextureFilter::nearest) {
      opt.interpmode = OIIO::TextureOpt::InterpClosest;
      opt.mipmode = OIIO::TextureOpt::MipModeNoMIP;
    } else {
      opt.interpmode = OIIO::TextureOpt::InterpBilinear;
      opt.mipmode = OIIO::TextureOpt::MipModeDefault;
    }
    const bool ok = m_ts->texture(static_cast<OIIO::TextureSystem::TextureHandle*>(texture), thread_info, opt, at.s,
                                  at.t, at.dsdx, at.dtdx, at.dsdy, at.dtdy, count, out);
    if (!ok) {
      for (int c = 0; c < count; ++c) out[c] = 0.0f;
      (void)m_ts->geterror();  // the error is the caller's to report; clear it
    }
    return ok;
  }

  TextureCacheStats statistics() override {
    TextureCacheStats s;
    OIIO::ImageCache* cache = m_ts->imagecache();
    // Each counter as the type this OpenImageIO keeps it in (some are 64-bit
    // in one release and 32-bit in another): a mismatched type reads nothing.
    auto count = [&](const char* name) -> std::uint64_t {
      long long i64 = 0;
      if (cache->getattribute(name, OIIO::TypeDesc::INT64, &i64)) return std::uint64_t(i64);
      int i32 = 0;
      if (cache->getattribute(name, OIIO::TypeDesc::INT, &i32)) return std::uint64_t(i32);
      return 0;
    };
    s.tile_lookups = count("stat:find_tile_calls");
    s.tiles_read = count("stat:tiles_created");
    s.bytes_read = count("stat:bytes_read");
    s.cache_bytes = count("stat:cache_memory_used");
    s.files = count("stat:unique_files");
    float f = 0;
    if (cache->getattribute("stat:fileio_time", OIIO::TypeDesc::FLOAT, &f)) s.file_io_s = f;
    s.cache_limit_bytes = std::uint64_t(m_cache_mb) << 20;
    return s;
  }

  std::vector<std::uint8_t> encode_8bit(const std::string& extension, int width, int height, int channels,
                                        const std::vector<std::uint8_t>& pixels) override {
    const std::string name = "preview" + extension;  // the format by its extension
    auto out = OIIO::ImageOutput::create(name);
    if (!out) throw failure("no image format for '" + extension + "'", OIIO::geterror());
    if (!out->supports("ioproxy")) throw std::runtime_error("the " + std::string(out->format_name()) +
                                                            " writer cannot write to memory");
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput proxy(bytes);
    OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    void* ptr = &proxy;
    spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &ptr);
    if (!out->open(name, spec)) throw failure("cannot encode it", out->geterror());
    if (!out->write_image(OIIO::TypeDesc::UINT8, pixels.data())) throw failure("cannot encode it", out->geterror());
    if (!out->close()) throw failure("cannot encode it", out->geterror());
    return {bytes.begin(), bytes.end()};
  }

  void write_8bit(const std::string& path, int width, int height, int channels,
                  const std::vector<std::uint8_t>& pixels) override {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) throw failure("no image format for its extension", OIIO::geterror());
    OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    if (!out->open(path, spec)) throw failure("cannot open it for writing", out->geterror());
    if (!out->write_image(OIIO::TypeDesc::UINT8, pixels.data())) throw failure("cannot write it", out->geterror());
    if (!out->close()) throw failure("cannot close it", out->geterror());
  }

 private:
  static OIIO::TextureOpt::Wrap oiio_wrap(TextureWrap w) {
    switch (w) {
      case TextureWrap::clamp: return OIIO::TextureOpt::WrapClamp;
      case TextureWrap::mirror: return OIIO::TextureOpt::WrapMirror;
      case TextureWrap::periodic: break;
    }
    return OIIO::TextureOpt::WrapPeriodic;
  }

  const MemoryFile* memory_file(const std::string& path) {
    const std::lock_guard<std::mutex> lock(m_memory_mutex);
    const auto it = m_memory.find(path);
    return it == m_memory.end() ? nullptr : it->second.get();
  }

  /// Opens `path` for reading: from memory when add_memory_file named it.
  OpenInput open_input(const std::string& path) {
    OpenInput open;
    if (const MemoryFile* file = memory_file(path))
      open.reader = std::make_unique<OIIO::Filesystem::IOMemReader>(file->bytes.data(), file->bytes.size());
    const OIIO::ImageSpec config = input_config(open.reader.get());
    open.in = OIIO::ImageInput::open(path, &config, open.reader.get());
    return open;
  }

  OIIO::TextureSystem* m_ts;
  int m_cache_mb = 0;
  std::mutex m_memory_mutex;
  std::map<std::string, std::unique_ptr<MemoryFile>> m_memory;  ///< never erased: the cache may reopen
};

}  // namespace
}  // namespace kappa

extern "C" kappa::ImageLibrary* kappa_image_library_create(int cache_mb) {
  return new kappa::OiioLibrary(cache_mb);
}
