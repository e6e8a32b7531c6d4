#include "telear/net/client_name.hpp"

namespace telear::net {

std::string describe_caller(const grpc::ServerContext& context) {
  constexpr std::size_t kShown = 64;
  const auto& metadata = context.client_metadata();
  const auto it = metadata.find(kClientNameMetadata);
  if (it == metadata.end()) return "unnamed client (" + context.peer() + ")";
  std::string name(it->second.data(), std::min(it->second.size(), kShown));
  for (char& c : name) {
    if (c < 0x20 || c > 0x7e) c = '?';
  }
  if (it->second.size() > kShown) name += "...";
  return name + " (" + context.peer() + ")";
}

}  // namespace telear::net
