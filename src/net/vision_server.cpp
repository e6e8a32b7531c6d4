#include "telear/net/vision_server.hpp"

#include <grpcpp/grpcpp.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <fstream>
#include <sstream>

#include "telear/net/server_credentials.hpp"
#include "telear/net/token_file.hpp"
#include "telear/net/vision_service.hpp"
#include "telear/vision/camera_file.hpp"

namespace telear::net {

struct VisionServer::Impl {
  std::unique_ptr<VisionPipeline> pipeline;
  std::unique_ptr<VisionServiceImpl> service;
  std::unique_ptr<grpc::Server> server;
  std::string address;
  int port = 0;
  double grace_s = 0.5;
  bool stopped = false;
};

VisionServer::VisionServer() : impl_(std::make_unique<Impl>()) {}

VisionServer::~VisionServer() {
  stop();
}

Result<std::unique_ptr<VisionServer>> VisionServer::create(VisionServerOptions options) {
  if (!options.source) return Error{"vision server: no source"};
  if (options.jpeg_quality < 1 || options.jpeg_quality > 100) {
    return Error{"vision server: JPEG quality " + std::to_string(options.jpeg_quality) +
                 " is outside 1..100"};
  }
  const auto colon = options.listen_address.rfind(':');
  if (colon == std::string::npos || colon + 1 >= options.listen_address.size()) {
    return Error{"vision server: listen address '" + options.listen_address + "' is not HOST:PORT"};
  }
  VisionServiceConfig config;
  config.max_streams = options.max_streams;
  std::string token = options.token;
  if (!options.token_file.empty()) {
    if (!token.empty()) return Error{"vision server: give the token or its file, not both"};
    auto loaded = load_token_file(options.token_file);
    if (!loaded) return Error{"vision server: " + loaded.error().message};
    token = std::move(loaded).value();
  }
  if (!options.observer_token_file.empty() && token.empty()) {
    return Error{"vision server: an observer token needs the operator's token (token_file)"};
  }
  if (!token.empty()) {
    std::string observer;
    if (!options.observer_token_file.empty()) {
      auto loaded = load_token_file(options.observer_token_file);
      if (!loaded) return Error{"vision server: observer token: " + loaded.error().message};
      if (*loaded == token) {
        return Error{"vision server: the observer token is the operator's token (it must differ)"};
      }
      observer = std::move(loaded).value();
    }
    config.auth.emplace(token, false, std::move(observer));
  }
  auto credentials = server_credentials(options.tls_cert_file, options.tls_key_file);
  if (!credentials) return Error{"vision server: " + credentials.error().message};
  if (!options.calibration_file.empty() || !options.calibration_yaml.empty()) {
    const bool from_file = !options.calibration_file.empty();
    const std::string name =
        from_file ? options.calibration_file : options.source->name() + " source's calibration";
    auto file = from_file ? vision::load_camera_file(options.calibration_file)
                          : vision::parse_camera_yaml(options.calibration_yaml, name);
    if (!file) return Error{"vision server: " + file.error().message};
    if (!file->is_stereo()) {
      return Error{"vision server: calibration '" + name +
                   "' is a mono camera file; a stereo file (left: and right:) is needed"};
    }
    std::string text = options.calibration_yaml;
    if (from_file) {
      std::ifstream in(options.calibration_file);
      std::ostringstream read;
      read << in.rdbuf();
      text = read.str();
    }
    config.calibration = std::move(*file);
    config.calibration_yaml = std::move(text);
  }

  std::unique_ptr<VisionServer> server(new VisionServer());
  Impl& impl = *server->impl_;
  impl.grace_s = options.shutdown_grace_s;
  VisionPipelineOptions pipeline_options;
  pipeline_options.default_quality = options.jpeg_quality;
  impl.pipeline = std::make_unique<VisionPipeline>(std::move(options.source), pipeline_options);
  if (auto started = impl.pipeline->start(); !started) {
    return Error{"vision server: " + started.error().message};
  }
  impl.service = std::make_unique<VisionServiceImpl>(*impl.pipeline, std::move(config));

  grpc::ServerBuilder builder;
  int port = 0;
  builder.AddListeningPort(options.listen_address, *credentials, &port);
  builder.RegisterService(impl.service.get());
  impl.server = builder.BuildAndStart();
  if (!impl.server || port == 0) {
    impl.pipeline->stop();
    return Error{"vision server: cannot listen on " + options.listen_address +
                 " (address in use, or not a local address?)"};
  }
  impl.port = port;
  impl.address = options.listen_address.substr(0, colon) + ":" + std::to_string(port);
  const vision::StereoSource& source = impl.pipeline->source();
  spdlog::info(
      "vision server listening on {} (source {}, {}x{} at {} fps, JPEG quality {}, {}, {})",
      impl.address, source.name(), source.width(), source.height(), source.fps(),
      options.jpeg_quality, token.empty() ? "no token" : "token required",
      options.tls_cert_file.empty() ? "plaintext" : "TLS");
  return server;
}

void VisionServer::stop() {
  if (!impl_ || impl_->stopped) return;
  impl_->stopped = true;
  if (impl_->service) impl_->service->begin_shutdown();
  if (impl_->pipeline) {
    // Close the slots first: every stream waiting for a frame returns at once.
    impl_->pipeline->stop();
  }
  if (impl_->server) {
    impl_->server->Shutdown(std::chrono::system_clock::now() +
                            std::chrono::milliseconds(static_cast<int>(impl_->grace_s * 1000)));
    impl_->server->Wait();
  }
  if (impl_->server) spdlog::info("vision server on {} shut down", impl_->address);
}

int VisionServer::port() const {
  return impl_->port;
}
std::string VisionServer::address() const {
  return impl_->address;
}
const VisionPipeline& VisionServer::pipeline() const {
  return *impl_->pipeline;
}
int VisionServer::active_streams() const {
  return impl_->service ? impl_->service->active_streams() : 0;
}

}  // namespace telear::net
