#pragma once
// Structure-of-arrays storage: one Field per scalar component, a contiguous row-major
// array (x fastest) with `ng` ghost layers all round; the row stride is a multiple of
// 64 bytes, the allocation is 64-byte aligned and padded in front so that the first
// interior element (0, j) of every row is 64-byte aligned (vector loads of a row's
// interior then never straddle a cache line).
// Cell-centred fields are nx x ny; x-face fields are (nx+1) x ny (face i is the left
// face of cell i); y-face fields are nx x (ny+1). Kernels see a Field through View,
// a pointer to element (0,0) plus the row stride.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <vector>

namespace refmap {

template <class T, std::size_t Align = 64>
struct AlignedAllocator {
  using value_type = T;
  AlignedAllocator() = default;
  template <class U> AlignedAllocator(const AlignedAllocator<U, Align>&) {}
  template <class U> struct rebind { using other = AlignedAllocator<U, Align>; };
  T* allocate(std::size_t n) {
    std::size_t bytes = ((n * sizeof(T) + Align - 1) / Align) * Align;
    void* p = std::aligned_alloc(Align, bytes ? bytes : Align);
    if (!p) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t) noexcept { std::free(p); }
  bool operator==(const AlignedAllocator&) const { return true; }
  bool operator!=(const AlignedAllocator&) const { return false; }
};

/// Non-owning 2-D view: v(i, j) = p[j * stride + i], i and j may be negative down to -ng.
template <class T>
struct View2 {
  T* p = nullptr;
  std::ptrdiff_t stride = 0;
  T& operator()(int i, int j) const { return p[std::ptrdiff_t(j) * stride + i]; }
  operator View2<const T>() const { return {p, stride}; }
};
using View = View2<double>;
using CView = View2<const double>;

/// 2-D array with ghost layers; Field (double) holds every physical quantity, Mask
/// (uint8_t) the solid flags.
template <class T>
class Array2 {
 public:
  Array2() = default;
  Array2(int nx, int ny, int ng = 2, T value = T{}) { resize(nx, ny, ng, value); }

  void resize(int nx, int ny, int ng = 2, T value = T{}) {
    nx_ = nx; ny_ = ny; ng_ = ng;
    // interior element (0, j) of every row 64-byte aligned: `lead_` padding elements before
    // the first ghost column, row stride a multiple of 64 bytes
    constexpr int A = int(64 / sizeof(T));
    lead_ = (A - ng % A) % A;
    stride_ = ((lead_ + nx + 2 * ng + A - 1) / A) * A;
    data_.assign(std::size_t(stride_) * std::size_t(ny + 2 * ng), value);
  }
  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int ng() const { return ng_; }
  std::ptrdiff_t stride() const { return stride_; }

  T& operator()(int i, int j) { return data_[idx(i, j)]; }
  T operator()(int i, int j) const { return data_[idx(i, j)]; }

  View2<T> view() { return {data_.data() + idx(0, 0), stride_}; }
  View2<const T> view() const { return {data_.data() + idx(0, 0), stride_}; }
  View2<const T> cview() const { return view(); }

  void fill(T v) { std::fill(data_.begin(), data_.end(), v); }
  T* raw() { return data_.data(); }
  const T* raw() const { return data_.data(); }
  std::size_t raw_size() const { return data_.size(); }

 private:
  std::size_t idx(int i, int j) const {
    return std::size_t(lead_) + std::size_t(j + ng_) * std::size_t(stride_) + std::size_t(i + ng_);
  }
  int nx_ = 0, ny_ = 0, ng_ = 0, lead_ = 0;
  std::ptrdiff_t stride_ = 0;
  std::vector<T, AlignedAllocator<T>> data_;
};

using Field = Array2<double>;
using Mask = Array2<std::uint8_t>;

}  // namespace refmap
