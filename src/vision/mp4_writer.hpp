#pragma once
// The MP4 writer of the videoio plugin (telear/vision/videoio.hpp): OpenCV's VideoWriter
// through FFmpeg, H.264 when this OpenCV can write it, else MPEG-4 part 2.
#include <memory>

#include "telear/vision/videoio.hpp"

namespace telear::vision {

Result<std::unique_ptr<VideoWriter>> open_opencv_mp4_writer(const VideoWriterOptions& options);

}  // namespace telear::vision
