#include "telear/net/bearer_auth.hpp"

#include <algorithm>
#include <cassert>
#include <utility>

namespace telear::net {

namespace {

constexpr const char* kScheme = "Bearer ";

std::string trim(const std::string& s) {
  const char* space = " \t\r\n\v\f";
  const auto first = s.find_first_not_of(space);
  if (first == std::string::npos) return "";
  const auto last = s.find_last_not_of(space);
  return s.substr(first, last - first + 1);
}

}  // namespace

bool constant_time_equal(const std::string& a, const std::string& b) {
  // Every byte of the longer string is visited; a length mismatch is folded in, not
  // returned early.
  const size_t n = std::max(a.size(), b.size());
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  for (size_t i = 0; i < n; ++i) {
    const unsigned char x = i < a.size() ? static_cast<unsigned char>(a[i]) : 0;
    const unsigned char y = i < b.size() ? static_cast<unsigned char>(b[i]) : 0;
    diff |= static_cast<unsigned char>(x ^ y);
  }
  return diff == 0;
}

BearerAuth::BearerAuth(std::string token, bool allow_observers, std::string observer_token)
    : token_(std::move(token)),
      allow_observers_(allow_observers),
      observer_token_(std::move(observer_token)) {
  assert(!token_.empty() && "BearerAuth: the token is empty");
  assert(observer_token_ != token_ && "BearerAuth: the observer token is the operator's");
}

BearerAuth::Presented BearerAuth::check(const grpc::ServerContext& context) const {
  const auto& metadata = context.client_metadata();
  const auto it = metadata.find("authorization");
  if (it == metadata.end()) return Presented::kNone;
  const std::string value(it->second.data(), it->second.size());
  const std::string scheme = kScheme;
  if (value.compare(0, scheme.size(), scheme) != 0) return Presented::kMalformed;
  const std::string presented = trim(value.substr(scheme.size()));
  if (constant_time_equal(presented, token_)) return Presented::kValid;
  if (!observer_token_.empty() && constant_time_equal(presented, observer_token_)) {
    return Presented::kObserver;
  }
  return Presented::kWrong;
}

grpc::Status BearerAuth::authorize_command(const grpc::ServerContext& context) const {
  switch (check(context)) {
    case Presented::kValid:
      return grpc::Status::OK;
    case Presented::kObserver:
      return {grpc::StatusCode::PERMISSION_DENIED,
              "read-only token: the observer token may read (info, state, video), commands need "
              "the operator's token"};
    case Presented::kNone:
      return {grpc::StatusCode::UNAUTHENTICATED,
              "no token: commands need the metadata 'authorization: Bearer <token>'"};
    case Presented::kMalformed:
      return {grpc::StatusCode::UNAUTHENTICATED,
              "malformed authorization metadata: expected 'Bearer <token>'"};
    case Presented::kWrong:
      break;
  }
  return {grpc::StatusCode::UNAUTHENTICATED, "wrong token"};
}

grpc::Status BearerAuth::authorize_read(const grpc::ServerContext& context) const {
  const Presented presented = check(context);
  if (presented == Presented::kObserver) return grpc::Status::OK;
  if (presented == Presented::kNone && allow_observers_) return grpc::Status::OK;
  if (presented == Presented::kNone) {
    return {grpc::StatusCode::UNAUTHENTICATED,
            "no token: this server does not allow observers; send 'authorization: Bearer "
            "<token>' (the operator's or the observer token)"};
  }
  return authorize_command(context);
}

}  // namespace telear::net
