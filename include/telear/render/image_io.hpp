#pragma once
// PNG output and PNG / JPEG input of core::Image (stb_image_write / stb_image, Debian's
// libstb). Files are untrusted: failures return an error naming the file and the reason.

#include <string>

#include "telear/core/image.hpp"
#include "telear/core/result.hpp"

namespace telear::render {

// Writes a 1-, 3- or 4-channel image as PNG.
Status write_png(const std::string& path, const core::Image& image);

// Reads a PNG / JPEG / BMP ... as RGB (channels = 3) or with its own channel count
// (desired_channels = 0).
Result<core::Image> read_image(const std::string& path, int desired_channels = 3);

}  // namespace telear::render
