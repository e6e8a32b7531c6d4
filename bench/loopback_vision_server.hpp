#pragma once
// The vision server the stream and latency benchmarks measure: the real server on 127.0.0.1
// (an ephemeral port) streaming the synthetic source at a fixed size and rate.

#include <memory>
#include <utility>

#include "telear/core/image_size.hpp"
#include "telear/core/result.hpp"
#include "telear/net/vision_server.hpp"
#include "telear/vision/synthetic_source.hpp"

namespace telear::cli {

inline Result<std::unique_ptr<net::VisionServer>> start_loopback_vision_server(
    core::ImageSize size, double fps, int jpeg_quality, bool frame_code = false) {
  vision::SyntheticSourceOptions source_options;
  source_options.width = size.width;
  source_options.height = size.height;
  source_options.fps = fps;
  source_options.frame_code = frame_code;
  auto source = vision::SyntheticSource::create(source_options);
  if (!source) return source.error();
  net::VisionServerOptions server_options;
  server_options.listen_address = "127.0.0.1:0";
  server_options.source = std::move(*source);
  server_options.jpeg_quality = jpeg_quality;
  return net::VisionServer::create(std::move(server_options));
}

}  // namespace telear::cli
