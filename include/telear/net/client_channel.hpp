#pragma once
// The gRPC channel every telear client opens: plaintext or TLS (options.tls_root_certificate_
// file), and gRPC's own reconnect back-off set from the options, so a restarted server is
// found again within reconnect_max_backoff_s (gRPC's default waits up to 120 s).

#include <grpcpp/grpcpp.h>

#include <memory>

#include "telear/net/client_options.hpp"

namespace telear::net {

// max_receive_bytes > 0 raises gRPC's 4 MB receive limit (the stereo stream's large frames).
std::shared_ptr<grpc::Channel> make_client_channel(const ClientOptions& options,
                                                   int max_receive_bytes = 0);

}  // namespace telear::net
