#include "telear/net/random_token.hpp"

#include <cassert>
#include <random>

namespace telear::net {

std::string random_token(std::size_t bytes) {
  assert(bytes > 0 && "random_token(): bytes must be positive");
  static constexpr char kHex[] = "0123456789abcdef";
  std::random_device device;
  std::string token;
  token.reserve(2 * bytes);
  unsigned word = 0;
  for (std::size_t i = 0; i < bytes; ++i) {
    // random_device yields 32 bits per call: four bytes each.
    if (i % 4 == 0) word = static_cast<unsigned>(device());
    const unsigned byte = (word >> (8 * (i % 4))) & 0xffu;
    token += kHex[byte >> 4];
    token += kHex[byte & 0xfu];
  }
  return token;
}

}  // namespace telear::net
