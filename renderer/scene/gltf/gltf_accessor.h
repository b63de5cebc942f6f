// A glTF accessor, checked before a byte of it is read: its buffer view and
// buffer exist, its elements lie inside both, the stride holds an element,
// and its component type and type are those its use allows. Refusals name
// the JSON pointer of the bad element. Reads are then bounds-free.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>

#include "core/vec2.h"
#include "core/vec3.h"
#include "renderer/scene/gltf/gltf_file.h"

namespace kappa {

class AccessorReader {
 public:
  /// Accessor `index`, used by the element at `user` (a JSON pointer) as
  /// `what` ("POSITION"): refused unless its type is `type` (TINYGLTF_TYPE_*)
  /// and its component type one of `component_types`; integer components of
  /// a non-index use must be normalized when `normalized_integers` is set.
  AccessorReader(const GltfFile& gltf, int index, const std::string& user, const std::string& what, int type,
                 std::initializer_list<int> component_types, bool normalized_integers = false);

  std::size_t count() const { return m_count; }
  std::string pointer() const { return m_pointer; }

  /// Element i's component c as a double (normalized integers mapped to
  /// [0, 1] as glTF specifies).
  double component(std::size_t i, int c) const;
  std::uint32_t index(std::size_t i) const { return std::uint32_t(component_raw(i, 0)); }
  Vec3d vec3(std::size_t i) const { return {component(i, 0), component(i, 1), component(i, 2)}; }
  Vec2f vec2(std::size_t i) const { return {float(component(i, 0)), float(component(i, 1))}; }

 private:
  double component_raw(std::size_t i, int c) const;

  const unsigned char* m_data = nullptr;  ///< the first element
  std::size_t m_count = 0, m_stride = 0;
  int m_component_type = 0, m_component_size = 0;
  bool m_normalized = false;
  std::string m_pointer;
};

}  // namespace kappa
