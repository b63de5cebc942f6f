#include "image_files.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <gtest/gtest.h>
#include <png.h>

#include <exception>

namespace kappa::test {

int ExrFile::channel(const std::string& name) const {
  for (std::size_t c = 0; c < channels.size(); ++c)
    if (channels[c] == name) return int(c);
  return -1;
}

std::vector<float> ExrFile::values(const std::string& name) const {
  const int c = channel(name);
  if (c < 0) {
    ADD_FAILURE() << "no channel " << name;
    return {};
  }
  std::vector<float> out;
  for (std::size_t i = std::size_t(c); i < pixels.size(); i += channels.size()) out.push_back(pixels[i]);
  return out;
}

namespace {
template <class T>
const T* attribute_of(const std::map<std::string, ExrFile::Attribute>& attributes, const std::string& name) {
  const auto it = attributes.find(name);
  return it == attributes.end() ? nullptr : std::get_if<T>(&it->second);
}
}  // namespace

std::string ExrFile::string_attribute(const std::string& name, const std::string& otherwise) const {
  const std::string* v = attribute_of<std::string>(attributes, name);
  return v ? *v : otherwise;
}
int ExrFile::int_attribute(const std::string& name, int otherwise) const {
  const int* v = attribute_of<int>(attributes, name);
  return v ? *v : otherwise;
}
float ExrFile::float_attribute(const std::string& name, float otherwise) const {
  const float* v = attribute_of<float>(attributes, name);
  return v ? *v : otherwise;
}
const double* ExrFile::double_attribute(const std::string& name) const { return attribute_of<double>(attributes, name); }

ExrFile read_exr_file(const std::filesystem::path& path) {
  ExrFile image;
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i window = header.dataWindow();
    image.width = window.max.x - window.min.x + 1;
    image.height = window.max.y - window.min.y + 1;
    for (auto c = header.channels().begin(); c != header.channels().end(); ++c) image.channels.push_back(c.name());
    const std::size_t nc = image.channels.size();
    image.pixels.resize(std::size_t(image.width) * std::size_t(image.height) * nc);
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < nc; ++c)
      frame.insert(image.channels[c], Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + c, window, nc * sizeof(float),
                                                       nc * sizeof(float) * std::size_t(image.width)));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    for (auto a = header.begin(); a != header.end(); ++a) {
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&a.attribute())) image.attributes[a.name()] = s->value();
      else if (const auto* i = dynamic_cast<const Imf::IntAttribute*>(&a.attribute())) image.attributes[a.name()] = i->value();
      else if (const auto* f = dynamic_cast<const Imf::FloatAttribute*>(&a.attribute())) image.attributes[a.name()] = f->value();
      else if (const auto* d = dynamic_cast<const Imf::DoubleAttribute*>(&a.attribute())) image.attributes[a.name()] = d->value();
    }
  } catch (const std::exception& e) {
    ADD_FAILURE() << "cannot read " << path << ": " << e.what();
    return {};
  }
  return image;
}

PngFile read_png_file(const std::filesystem::path& path) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str())) {
    ADD_FAILURE() << "cannot read " << path << ": " << png.message;
    return {};
  }
  png.format = PNG_FORMAT_RGB;
  PngFile image;
  image.width = int(png.width);
  image.height = int(png.height);
  image.rgb.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr)) {
    ADD_FAILURE() << "cannot decode " << path << ": " << png.message;
    png_image_free(&png);
    return {};
  }
  return image;
}

}  // namespace kappa::test
