#pragma once
// Working storage for the evaluation loops: on the stack up to N doubles, on the heap
// only beyond (degrees above about 12), so evaluation allocates nothing per point for
// every degree used in practice and still works for any degree.

#include <array>
#include <cstddef>
#include <memory>

namespace freeturn::nurbs {

template <std::size_t N>
class ScratchBuffer {
 public:
  explicit ScratchBuffer(std::size_t size) {
    if (size > N) {
      heap_ = std::make_unique<double[]>(size);
      data_ = heap_.get();
    } else {
      data_ = stack_.data();
    }
  }
  ScratchBuffer(const ScratchBuffer&) = delete;
  ScratchBuffer& operator=(const ScratchBuffer&) = delete;

  double* data() { return data_; }
  double& operator[](std::size_t i) { return data_[i]; }

 private:
  std::array<double, N> stack_;
  std::unique_ptr<double[]> heap_;
  double* data_;
};

}  // namespace freeturn::nurbs
