#pragma once
// A fixed-capacity ring buffer: the newest `capacity` elements in arrival order, the oldest
// overwritten when full. Its storage is allocated once, at construction, and push() hands back
// the slot to fill, so an element that owns memory (an Eigen::VectorXd of the same size) is
// reused in place: a buffer fed at a display's or a servo's rate allocates nothing per sample.
// The live plots' series (telear/session/live_series.hpp) are kept in these.
//
// Indexing is oldest first: (*this)[0] is the oldest element, (*this)[size() - 1] the newest.
// A plain value class, not thread-safe.

#include <cassert>
#include <cstddef>
#include <vector>

namespace telear::core {

template <typename T>
class RingBuffer {
 public:
  // capacity >= 1 (asserted).
  explicit RingBuffer(std::size_t capacity) : slots_(capacity) { assert(capacity >= 1); }

  std::size_t capacity() const { return slots_.size(); }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == slots_.size(); }

  // The slot of a new newest element, holding whatever an earlier element left there (fill
  // every field); when full, the oldest element's slot.
  T& push() {
    const std::size_t slot = (first_ + size_) % slots_.size();
    if (full()) {
      first_ = (first_ + 1) % slots_.size();
    } else {
      ++size_;
    }
    return slots_[slot];
  }
  void push(const T& value) { push() = value; }

  // Drops the oldest element; not empty (asserted).
  void pop_front() {
    assert(!empty());
    first_ = (first_ + 1) % slots_.size();
    --size_;
  }
  void clear() { first_ = size_ = 0; }

  // i < size() (asserted): 0 the oldest.
  const T& operator[](std::size_t i) const {
    assert(i < size_);
    return slots_[(first_ + i) % slots_.size()];
  }
  T& operator[](std::size_t i) {
    assert(i < size_);
    return slots_[(first_ + i) % slots_.size()];
  }
  const T& front() const { return (*this)[0]; }
  const T& back() const { return (*this)[size_ - 1]; }
  T& back() { return (*this)[size_ - 1]; }

 private:
  std::vector<T> slots_;
  std::size_t first_ = 0;  // the oldest element's slot
  std::size_t size_ = 0;
};

}  // namespace telear::core
