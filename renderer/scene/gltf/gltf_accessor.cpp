#include "renderer/scene/gltf/gltf_accessor.h"

#include <cstring>
#include <limits>

namespace kappa {
namespace {

const char* component_name(int t) {
  switch (t) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE (5120)";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE (5121)";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT (5122)";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT (5123)";
    case TINYGLTF_COMPONENT_TYPE_INT: return "INT (5124)";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT (5125)";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT (5126)";
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return "DOUBLE (5130)";
    default: return nullptr;
  }
}

const char* type_name(int t) {
  switch (t) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "an unknown type";
  }
}

}  // namespace

AccessorReader::AccessorReader(const GltfFile& gltf, int index, const std::string& user, const std::string& what,
                               int type, std::initializer_list<int> component_types, bool normalized_integers) {
  const std::filesystem::path& file = gltf.file;
  const tinygltf::Model& model = gltf.model;
  if (index < 0 || std::size_t(index) >= model.accessors.size())
    fail(file, 0, user + ": " + what + " names accessor " + std::to_string(index) + ", which does not exist (" +
                      std::to_string(model.accessors.size()) + " accessors)");
  m_pointer = json_pointer({"accessors", std::to_string(index)});
  const tinygltf::Accessor& a = model.accessors[std::size_t(index)];
  const std::string usage = " (" + what + " of " + user + ")";
  if (a.sparse.isSparse) fail(file, 0, m_pointer + ": sparse accessors are not read" + usage);
  if (!component_name(a.componentType))
    fail(file, 0, m_pointer + "/componentType: " + std::to_string(a.componentType) + " is not a glTF component type");
  bool allowed = false;
  std::string allowed_names;
  for (int t : component_types) {
    allowed |= t == a.componentType;
    allowed_names += std::string(allowed_names.empty() ? "" : " or ") + component_name(t);
  }
  if (!allowed)
    fail(file, 0, m_pointer + "/componentType: " + component_name(a.componentType) + usage + " must be " + allowed_names);
  if (a.type != type)
    fail(file, 0, m_pointer + "/type: " + type_name(a.type) + usage + " must be " + type_name(type));
  m_component_type = a.componentType;
  m_component_size = tinygltf::GetComponentSizeInBytes(std::uint32_t(a.componentType));
  m_normalized = a.normalized;
  if (normalized_integers && a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !a.normalized)
    fail(file, 0, m_pointer + "/normalized: integer components" + usage + " must be normalized");
  if (a.count < 1) fail(file, 0, m_pointer + "/count: must be at least 1");
  m_count = a.count;
  const std::size_t components = std::size_t(tinygltf::GetNumComponentsInType(std::uint32_t(a.type)));
  const std::size_t element = std::size_t(m_component_size) * components;
  // Without a buffer view the specification's accessor is all zeros (what
  // sparse accessors start from, which Kappa refuses): no geometry to read,
  // and a count with nothing behind it to bound it.
  if (a.bufferView < 0) fail(file, 0, m_pointer + ": no bufferView (all zeros): not read" + usage);
  if (std::size_t(a.bufferView) >= model.bufferViews.size())
    fail(file, 0, m_pointer + "/bufferView: " + std::to_string(a.bufferView) + " does not exist (" +
                      std::to_string(model.bufferViews.size()) + " buffer views)");
  const std::string view_pointer = json_pointer({"bufferViews", std::to_string(a.bufferView)});
  const tinygltf::BufferView& view = model.bufferViews[std::size_t(a.bufferView)];
  if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size())
    fail(file, 0, view_pointer + "/buffer: " + std::to_string(view.buffer) + " does not exist");
  const std::vector<unsigned char>& buffer = model.buffers[std::size_t(view.buffer)].data;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
    fail(file, 0, view_pointer + ": bytes " + std::to_string(view.byteOffset) + " to " +
                      std::to_string(view.byteOffset + view.byteLength) + " lie outside its buffer's " +
                      std::to_string(buffer.size()) + " bytes");
  m_stride = view.byteStride == 0 ? element : view.byteStride;
  if (m_stride < element)
    fail(file, 0, view_pointer + "/byteStride: " + std::to_string(view.byteStride) + " is less than the " +
                      std::to_string(element) + "-byte elements of " + m_pointer);
  // The last element's end, without overflow.
  const std::size_t max = std::numeric_limits<std::size_t>::max();
  if (a.byteOffset > view.byteLength || (m_count - 1) > (max - element) / m_stride ||
      (m_count - 1) * m_stride + element > view.byteLength - a.byteOffset)
    fail(file, 0, m_pointer + ": " + std::to_string(m_count) + " elements from byte " + std::to_string(a.byteOffset) +
                      " run past the " + std::to_string(view.byteLength) + " bytes of " + view_pointer);
  m_data = buffer.data() + view.byteOffset + a.byteOffset;
}

double AccessorReader::component_raw(std::size_t i, int c) const {
  if (!m_data) return 0.0;
  const unsigned char* p = m_data + i * m_stride + std::size_t(c) * std::size_t(m_component_size);
  switch (m_component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return double(*p);
    case TINYGLTF_COMPONENT_TYPE_BYTE: return double(static_cast<signed char>(*p));
    default: return 0.0;  // the constructor admits no other
  }
}

double AccessorReader::component(std::size_t i, int c) const {
  const double v = component_raw(i, c);
  if (!m_normalized) return v;
  switch (m_component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return v / 255.0;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return v / 65535.0;
    case TINYGLTF_COMPONENT_TYPE_BYTE: return std::max(v / 127.0, -1.0);
    case TINYGLTF_COMPONENT_TYPE_SHORT: return std::max(v / 32767.0, -1.0);
    default: return v;
  }
}

}  // namespace kappa
