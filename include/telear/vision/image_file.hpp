#pragma once
// Image files (calibration images, capture folders, coverage images) read and written without
// OpenCV's imgcodecs: Debian's imgcodecs loads 140 shared libraries (GDAL, Poppler, HDF5, ...)
// into every program that links vision, ~70 ms of dynamic linking at each start, and vision
// only ever needs the formats a camera or a capture writes. stb_image reads PNG (8 and 16
// bits), JPEG, BMP, TGA, PNM and GIF; PNG is written through libpng with the fast settings
// OpenCV's own writer uses (level 1, the Sub filter, run-length strategy). Images keep
// OpenCV's conventions: colour is BGR(A), rows top to bottom. EXIF orientation is not applied
// (a camera's frames are stored as captured).

#include <opencv2/core.hpp>
#include <string>

#include "telear/core/result.hpp"

namespace telear::vision {

enum class ImageFileMode {
  kGrey,       // 8-bit, one channel (colour converted with OpenCV's BT.601 weights)
  kColour,     // 8-bit BGR (a grey file repeated in three channels)
  kUnchanged,  // the file's channels (grey, BGR, BGRA) and depth (8 or 16 bits)
};

// The image at `path`, or an error naming the file and why it cannot be read.
Result<cv::Mat> read_image_file(const std::string& path, ImageFileMode mode);

// Writes a PNG: 8- or 16-bit, 1 (grey), 3 (BGR) or 4 (BGRA) channels.
Status write_png_file(const std::string& path, const cv::Mat& image);

}  // namespace telear::vision
