#pragma once
/// Raw memory that holds arrays of different trivial types at different times.
///
/// Why: the solver's largest transient arrays are never alive together. The pair list's
/// reference positions (3 floats a particle) are needed between rebuilds; the grid's
/// sort keys and slot order (12 bytes a particle) only during one. One buffer serves
/// both, which keeps the solver near its memory goal (docs/architecture.md, "Memory").
#include <cstddef>
#include <memory>
#include <new>
#include <span>
#include <type_traits>

namespace softsub {

/// Starts the lifetime of `count` objects of T in the storage at `p` (suitably aligned),
/// ending whatever lived there; their values are unspecified until written. Generates
/// no code: it only tells the compiler that the storage changed type (C++20 implicit
/// object creation by a std::byte array).
template <class T>
T* reuseStorageAs(std::byte* p, std::size_t count) {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);
  if (count == 0) return nullptr;
  return std::launder(reinterpret_cast<T*>(::new (static_cast<void*>(p)) std::byte[count * sizeof(T)]));
}

/// A growable block of raw bytes, aligned for any scalar type.
class WorkBuffer {
 public:
  /// Makes room for at least `bytes`; when it grows, the contents are lost.
  void reserve(std::size_t bytes) {
    if (bytes <= size_) return;
    data_ = std::make_unique_for_overwrite<std::byte[]>(bytes);
    size_ = bytes;
  }
  /// The whole buffer.
  [[nodiscard]] std::span<std::byte> bytes() { return {data_.get(), size_}; }
  /// Bytes held.
  [[nodiscard]] std::size_t size() const { return size_; }

 private:
  std::unique_ptr<std::byte[]> data_;
  std::size_t size_ = 0;
};

}  // namespace softsub
