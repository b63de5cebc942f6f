// A fixed-size array that starts as zeros without writing them: fresh
// anonymous pages are zero until touched, so the per-cell counters of cells
// no ray visits cost neither the time to clear them nor memory traffic (a
// std::vector writes every byte when it is created). Blocks of 2 MiB and
// more are mapped for transparent huge pages (core/huge_pages.h): a first
// touch of a 4 KiB page costs about 12 us on the project's VMs, which made
// the per-cell counters of a large grid cost seconds however few the rays.
#pragma once

#include "core/huge_pages.h"

#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>

namespace kappa {

template <class T>
class ZeroedArray {
  static_assert(std::is_trivially_copyable_v<T>, "zero bytes must be a valid T");

 public:
  ZeroedArray() = default;
  explicit ZeroedArray(std::size_t n) : m_data(allocate(n)), m_size(n) {}
  ZeroedArray(const ZeroedArray& o) : m_data(allocate(o.m_size)), m_size(o.m_size) {
    if (m_size > 0) std::memcpy(m_data.get(), o.m_data.get(), m_size * sizeof(T));
  }
  ZeroedArray& operator=(const ZeroedArray& o) {
    if (this != &o) *this = ZeroedArray(o);
    return *this;
  }
  // A moved-from array is empty (size 0), not a size without data.
  ZeroedArray(ZeroedArray&& o) noexcept : m_data(std::move(o.m_data)), m_size(std::exchange(o.m_size, 0)) {}
  ZeroedArray& operator=(ZeroedArray&& o) noexcept {
    m_data = std::move(o.m_data);
    m_size = std::exchange(o.m_size, 0);
    return *this;
  }

  std::size_t size() const { return m_size; }
  bool empty() const { return m_size == 0; }
  T* data() { return m_data.get(); }
  const T* data() const { return m_data.get(); }
  T& operator[](std::size_t i) { return m_data[i]; }
  const T& operator[](std::size_t i) const { return m_data[i]; }
  const T* begin() const { return data(); }
  const T* end() const { return data() + m_size; }

 private:
  struct Free {
    std::size_t bytes = 0;
    void operator()(T* p) const {
      if (bytes >= kHugePageBytes) release_huge_pages(p, bytes);
      else std::free(p);
    }
  };
  static std::unique_ptr<T[], Free> allocate(std::size_t n) {
    if (n == 0) return {nullptr, Free{}};
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_alloc();
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= kHugePageBytes) return {static_cast<T*>(map_huge_pages(bytes)), Free{bytes}};
    void* p = std::calloc(n, sizeof(T));
    if (!p) throw std::bad_alloc();
    return {static_cast<T*>(p), Free{bytes}};
  }

  std::unique_ptr<T[], Free> m_data;
  std::size_t m_size = 0;
};

}  // namespace kappa
