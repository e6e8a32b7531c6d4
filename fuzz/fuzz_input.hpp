#pragma once
// What every harness shares: libFuzzer's entry point, and the input as text. A harness calls
// the function telear calls on that door with the bytes as they come; it checks nothing
// itself -- a crash, a sanitizer report, a leak or a hang is the finding (docs/fuzzing.md).

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace telear::fuzz {

inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// The first byte picks one of `n` variants of a door (0 when empty); the rest is the input.
inline std::size_t pick(const std::uint8_t*& data, std::size_t& size, std::size_t n) {
  if (size == 0) return 0;
  const std::size_t choice = data[0] % n;
  ++data;
  --size;
  return choice;
}

// Which of `n` doors (the first byte) and the text for it (the rest).
struct DoorInput {
  std::size_t door = 0;
  std::string text;
};
inline DoorInput door_input(const std::uint8_t* data, std::size_t size, std::size_t n) {
  const std::size_t door = pick(data, size, n);
  return {door, fuzz::text(data, size)};
}

// Structure from bytes, for a door whose input is fields rather than text (a ROS message):
// numbers are taken as their bytes (zero once the input runs out), strings as a length byte
// and that many bytes. Seeds are written in the same layout (fuzz/seeds/*.py).
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  template <typename T>
  T take() {
    T value{};
    const std::size_t n = sizeof(T) < size_ ? sizeof(T) : size_;
    std::memcpy(&value, data_, n);
    data_ += n;
    size_ -= n;
    return value;
  }
  std::string string() {
    const std::size_t length = take<std::uint8_t>();
    const std::size_t n = length < size_ ? length : size_;
    std::string s(reinterpret_cast<const char*>(data_), n);
    data_ += n;
    size_ -= n;
    return s;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
};

}  // namespace telear::fuzz
