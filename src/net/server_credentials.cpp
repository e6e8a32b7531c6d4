#include "telear/net/server_credentials.hpp"

#include <grpcpp/security/server_credentials.h>

#include <fstream>
#include <sstream>

namespace telear::net {
namespace {

Result<std::string> read_pem(const std::string& path, const char* what, const char* label) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{std::string("cannot read the TLS ") + what + " '" + path + "'"};
  std::ostringstream text;
  text << in.rdbuf();
  // "-----BEGIN CERTIFICATE-----", "-----BEGIN PRIVATE KEY-----" / "... EC PRIVATE KEY-----":
  // a wrong file is said here rather than as gRPC's handshake failure later.
  if (text.str().find("-----BEGIN ") == std::string::npos ||
      text.str().find(label) == std::string::npos) {
    return Error{"the TLS " + std::string(what) + " '" + path + "' is not a PEM " + what};
  }
  return text.str();
}

}  // namespace

Result<std::shared_ptr<grpc::ServerCredentials>> server_credentials(const std::string& cert_file,
                                                                    const std::string& key_file) {
  if (cert_file.empty() && key_file.empty()) return grpc::InsecureServerCredentials();
  if (cert_file.empty() != key_file.empty()) {
    return Error{"TLS needs both a certificate and a key file, got only the " +
                 std::string(cert_file.empty() ? "key" : "certificate")};
  }
  auto cert = read_pem(cert_file, "certificate", "CERTIFICATE-----");
  if (!cert) return cert.error();
  auto key = read_pem(key_file, "key", "PRIVATE KEY-----");
  if (!key) return key.error();
  grpc::SslServerCredentialsOptions ssl;
  ssl.pem_key_cert_pairs.push_back({*key, *cert});
  return grpc::SslServerCredentials(ssl);
}

}  // namespace telear::net
