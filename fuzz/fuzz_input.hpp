#pragma once
// What every harness shares: libFuzzer's entry point, and the input as text. A harness calls
// the function telear calls on that door with the bytes as they come; it checks nothing
// itself -- a crash, a sanitizer report, a leak or a hang is the finding (docs/fuzzing.md).

#include <cstddef>
#include <cstdint>
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

}  // namespace telear::fuzz
