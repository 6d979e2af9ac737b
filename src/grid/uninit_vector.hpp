// A vector for large arrays whose every element is written once after
// allocation (the HGrid's arrays, the buffers of the decomposed search):
// resize() leaves trivial elements unwritten instead of zeroing them first
// (a whole pass over tens of MB at N = 10^6).
#pragma once
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace hgrid {

template <class T>
struct UninitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitAllocator<U>;
  };
  UninitAllocator() = default;
  template <class U>
  UninitAllocator(const UninitAllocator<U>&) noexcept {}
  /// Value-initialisation (resize, the vector(n) constructor) becomes
  /// default-initialisation; everything else constructs as usual.
  template <class U>
  void construct(U* p) noexcept(noexcept(::new(static_cast<void*>(p)) U)) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... A>
  void construct(U* p, A&&... a) {
    ::new (static_cast<void*>(p)) U(std::forward<A>(a)...);
  }
};

/// A vector whose resize() leaves new trivial elements unwritten.
template <class T>
using UninitVector = std::vector<T, UninitAllocator<T>>;

namespace detail {
using hgrid::UninitAllocator;
using hgrid::UninitVector;
}  // namespace detail

}  // namespace hgrid
