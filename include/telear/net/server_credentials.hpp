#pragma once
// The credentials a telear server listens with: TLS from a PEM certificate (chain) and its
// private key, or plaintext when neither is given -- one function for the robot and the vision
// server, so both take --tls-cert / --tls-key alike (docs/network.md, "TLS").

#include <grpcpp/security/server_credentials.h>

#include <memory>
#include <string>

#include "telear/core/result.hpp"

namespace telear::net {

// Errors: only one of the two files given ("TLS needs both a certificate and a key file, got
// only the key"), a file that cannot be read (named), a file that is not PEM ("... is not a
// PEM certificate"). gRPC itself checks that the key matches the certificate when it listens.
Result<std::shared_ptr<grpc::ServerCredentials>> server_credentials(const std::string& cert_file,
                                                                    const std::string& key_file);

}  // namespace telear::net
