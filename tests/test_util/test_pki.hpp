#pragma once
// A throwaway PKI made for a test by Debian's openssl (EC P-256 keys: quick to make): a CA, a
// server certificate it signs for localhost / 127.0.0.1, another CA, and a certificate the
// first CA signs for another host. The servers' TLS tests (net) and telear web's HTTPS test
// (web) start their servers with them.

#include <string>

#include "test_util/temp_dir.hpp"

namespace telear::test_files {

struct TestPki {
  std::string ca, other_ca, server_cert, server_key, other_host_cert, other_host_key;
};

// The files, in `dir`; a failing openssl command is a test failure (EXPECT).
TestPki make_test_pki(const TempDir& dir);

}  // namespace telear::test_files
