#pragma once
// Bearer-token authentication of gRPC calls: the client sends the metadata
//   authorization: Bearer <token>
// and the server compares the token with its own in constant time (the comparison takes as
// long whatever prefix matches, so timing reveals nothing about the token).
//
// Two kinds of access:
//   command  needs the operator's token;
//   read     (info, state, ping) needs the operator's token, or the observer token (a second,
//            read-only token for watchers: a recorder, a dashboard), or none at all when
//            observers are allowed (off by default: the URDF, the workspace and the arm's state
//            are the lab's). A wrong token is refused even where none would do: a client that
//            sends one means to be an operator, and should learn at once that it is not.
// Refusals are UNAUTHENTICATED statuses whose message says what was missing or wrong; the
// observer token presented for a command is PERMISSION_DENIED ("read-only").

#include <grpcpp/grpcpp.h>

#include <string>

#include "telear/core/result.hpp"

namespace telear::net {

// true when a and b are equal; the time taken depends on the lengths only.
bool constant_time_equal(const std::string& a, const std::string& b);

class BearerAuth {
 public:
  // `token` must not be empty (asserts); `observer_token` empty: none (it must differ from
  // `token`, asserted).
  BearerAuth(std::string token, bool allow_observers, std::string observer_token = {});

  bool allow_observers() const { return allow_observers_; }

  grpc::Status authorize_command(const grpc::ServerContext& context) const;
  grpc::Status authorize_read(const grpc::ServerContext& context) const;

 private:
  enum class Presented { kNone, kValid, kObserver, kWrong, kMalformed };
  Presented check(const grpc::ServerContext& context) const;

  std::string token_;
  bool allow_observers_;
  std::string observer_token_;
};

}  // namespace telear::net
