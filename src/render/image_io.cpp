#include "telear/render/image_io.hpp"

#include <stb_image.h>
#include <stb_image_write.h>

#include <cstring>

namespace telear::render {

Status write_png(const std::string& path, const core::Image& image) {
  if (image.empty() || image.width <= 0 || image.height <= 0 ||
      (image.channels != 1 && image.channels != 3 && image.channels != 4) ||
      image.pixels.size() != image.row_bytes() * static_cast<std::size_t>(image.height)) {
    return Error{"cannot write '" + path + "': not a valid 1-, 3- or 4-channel image"};
  }
  const int ok = stbi_write_png(path.c_str(), image.width, image.height, image.channels,
                                image.pixels.data(), static_cast<int>(image.row_bytes()));
  if (ok == 0) return Error{"cannot write PNG file '" + path + "'"};
  return Status::Ok();
}

Result<core::Image> read_image(const std::string& path, int desired_channels) {
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, desired_channels);
  if (data == nullptr) {
    const char* reason = stbi_failure_reason();
    return Error{"cannot read image '" + path + "': " + (reason ? reason : "unknown reason")};
  }
  core::Image image(w, h, desired_channels > 0 ? desired_channels : n);
  std::memcpy(image.pixels.data(), data, image.pixels.size());
  stbi_image_free(data);
  return image;
}

}  // namespace telear::render
