#pragma once
// The client's name on the wire. Every call of a telear client carries the metadata
//   telear-client: <ClientOptions::client_name>
// (ClientBase, telear/net/client_base.hpp, adds it), and both servers name the caller in their
// logs with describe_caller(): "alice (ipv4:127.0.0.1:40112)", the name and the peer. The
// name is the client's own claim, for the log only: authority comes from the bearer token.

#include <grpcpp/grpcpp.h>

#include <string>

namespace telear::net {

inline constexpr const char* kClientNameMetadata = "telear-client";

// "NAME (PEER)"; "unnamed client (PEER)" without the metadata. The name is untrusted text:
// non-printable bytes become '?' and it is cut after 64 characters ("...").
std::string describe_caller(const grpc::ServerContext& context);

}  // namespace telear::net
