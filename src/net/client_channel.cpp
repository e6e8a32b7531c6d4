#include "telear/net/client_channel.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

namespace telear::net {

std::shared_ptr<grpc::Channel> make_client_channel(const ClientOptions& options,
                                                   int max_receive_bytes) {
  grpc::ChannelArguments args;
  const int initial_ms = std::max(1, static_cast<int>(options.reconnect_initial_backoff_s * 1e3));
  const int max_ms = std::max(initial_ms, static_cast<int>(options.reconnect_max_backoff_s * 1e3));
  args.SetInt(GRPC_ARG_INITIAL_RECONNECT_BACKOFF_MS, initial_ms);
  args.SetInt(GRPC_ARG_MIN_RECONNECT_BACKOFF_MS, initial_ms);
  args.SetInt(GRPC_ARG_MAX_RECONNECT_BACKOFF_MS, max_ms);
  if (max_receive_bytes > 0) args.SetMaxReceiveMessageSize(max_receive_bytes);
  std::shared_ptr<grpc::ChannelCredentials> credentials = grpc::InsecureChannelCredentials();
  if (!options.tls_root_certificate_file.empty()) {
    std::ifstream in(options.tls_root_certificate_file, std::ios::binary);
    std::ostringstream pem;
    pem << in.rdbuf();
    grpc::SslCredentialsOptions ssl;
    ssl.pem_root_certs = pem.str();
    credentials = grpc::SslCredentials(ssl);
  }
  return grpc::CreateCustomChannel(options.address, credentials, args);
}

}  // namespace telear::net
