#pragma once
// Random secrets for the servers: bearer tokens (session/EmbeddedServers) and lease ids
// (net/LeaseManager). One generator, so every secret telear makes has the same source and
// alphabet.
//
// random_token(bytes) draws `bytes` bytes from std::random_device (the OS's entropy source,
// /dev/urandom or the CPU's RDRAND on Linux with libstdc++) and writes them as 2 * bytes
// lower-case hex digits, so a token is safe in metadata, file names and log lines. 16 bytes
// (128 bits) is the default: guessing one is out of reach, and it fits one log line.
// Thread-safe: each call has its own std::random_device.

#include <cstddef>
#include <string>

namespace telear::net {

// 2 * bytes hex digits ('0'-'9', 'a'-'f'); bytes must be positive (asserts).
std::string random_token(std::size_t bytes = 16);

}  // namespace telear::net
