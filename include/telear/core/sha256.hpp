#pragma once
// SHA-256 (FIPS 180-4) of a byte string, as 64 lowercase hex digits, through OpenSSL's
// libcrypto EVP interface (linked privately into telear::core: no OpenSSL header leaks out).
// Used to fingerprint plans (telear/core/plan_hash.hpp); not a security boundary by itself.

#include <string>
#include <string_view>

namespace telear::core {

// sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
std::string sha256_hex(std::string_view bytes);

}  // namespace telear::core
