#pragma once
// VisionServer: a running VisionService (telear/net/vision_service.hpp) over its VisionPipeline
// (telear/net/vision_pipeline.hpp), listening on a TCP address.
//
// Lifetime. start() loads the calibration and token files, starts the pipeline (the source's
// prepare() runs there: a sim rig's GL context, for instance) and the gRPC server, and returns
// once it accepts calls (port 0 in the address: an ephemeral port, see port()). stop() (or the
// destructor) shuts down cleanly with clients streaming: the service's loops are told to end,
// gRPC is given a short deadline to finish the calls (then cancels them: a Write blocked on a
// client that stopped reading returns), and the pipeline's threads are joined.
//
// Log: through spdlog (telear/net/server_log.hpp), like the robot server: the address once
// listening, every stream with the client's name, errors, the shutdown.

#include <memory>
#include <string>

#include "telear/core/result.hpp"
#include "telear/net/vision_pipeline.hpp"
#include "telear/vision/stereo_source.hpp"

namespace telear::net {

struct VisionServerOptions {
  std::string listen_address = "127.0.0.1:50052";  // host:port; port 0: ephemeral
  std::unique_ptr<vision::StereoSource> source;    // required
  std::string calibration_file;  // optional stereo camera file (OpenCV YAML) for GetCameraInfo
  std::string token_file;        // optional: every call needs `authorization: Bearer <token>`
  std::string token;             // or the token itself (servers started in-process); not both
  // A second accepted token (the vision service only reads): the robot server's observer token
  // for watchers; empty: none. Needs token_file.
  std::string observer_token_file;
  std::string tls_cert_file;  // PEM; with tls_key_file: TLS (net/server_credentials.hpp)
  std::string tls_key_file;
  int jpeg_quality = 85;  // the shared encode's quality
  int max_streams = 16;
  double shutdown_grace_s = 0.5;  // how long streaming calls get to finish before cancellation
  // Without calibration_file: the text of a stereo camera file the source knows itself (the ROS
  // source's, from camera_info), read and checked as a file would be; empty: none.
  std::string calibration_yaml;
};

class VisionServer {
 public:
  static Result<std::unique_ptr<VisionServer>> create(VisionServerOptions options);
  ~VisionServer();  // stop()
  VisionServer(const VisionServer&) = delete;
  VisionServer& operator=(const VisionServer&) = delete;

  void stop();
  int port() const;
  std::string address() const;  // host:port actually bound
  const VisionPipeline& pipeline() const;
  int active_streams() const;

 private:
  struct Impl;
  VisionServer();
  std::unique_ptr<Impl> impl_;
};

}  // namespace telear::net
