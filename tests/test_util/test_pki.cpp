#include "test_util/test_pki.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

namespace telear::test_files {

namespace {

bool run_quietly(const std::string& command) {
  return std::system((command + " > /dev/null 2>&1").c_str()) == 0;
}

}  // namespace

TestPki make_test_pki(const TempDir& dir) {
  const auto f = [&](const std::string& name) { return dir.file(name); };
  const std::string key_args = "-newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes";
  for (const char* ca : {"ca", "other_ca"}) {
    EXPECT_TRUE(run_quietly("openssl req -x509 " + key_args + " -keyout " +
                            f(std::string(ca) + ".key") + " -out " + f(std::string(ca) + ".crt") +
                            " -days 2 -subj /CN=telear-test-" + ca));
  }
  // A server certificate signed by `ca` for `names` (subjectAltName).
  const auto server = [&](const std::string& name, const std::string& names) {
    std::ofstream(f(name + ".ext")) << "subjectAltName=" << names << "\n";
    EXPECT_TRUE(run_quietly("openssl req " + key_args + " -keyout " + f(name + ".key") + " -out " +
                            f(name + ".csr") + " -subj /CN=" + name));
    EXPECT_TRUE(run_quietly("openssl x509 -req -in " + f(name + ".csr") + " -CA " + f("ca.crt") +
                            " -CAkey " + f("ca.key") + " -CAcreateserial -days 2 -out " +
                            f(name + ".crt") + " -extfile " + f(name + ".ext")));
  };
  server("server", "DNS:localhost,IP:127.0.0.1");
  server("elsewhere", "DNS:robot.elsewhere.example");
  return {f("ca.crt"),     f("other_ca.crt"),  f("server.crt"),
          f("server.key"), f("elsewhere.crt"), f("elsewhere.key")};
}

}  // namespace telear::test_files
