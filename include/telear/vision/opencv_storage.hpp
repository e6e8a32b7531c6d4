#pragma once
// OpenCV FileStorage text in its two common layouts, YAML ("%YAML:1.0") and XML
// ("<opencv_storage>"), converted into each other through cv::FileStorage itself, so that
// every camera and calibration file telear reads or writes in one layout exists in the other
// with the same keys: the XML readers feed the YAML parsers (one set of checks and messages),
// and the writers turn their YAML into XML when the target path ends in ".xml".
//
// The conversion keeps maps, sequences, integers, reals (to the last bit: OpenCV writes
// doubles with 17 significant digits), strings and OpenCV matrices (a map of rows, cols, dt
// and data is written back as a matrix of that type). Comments are not kept.

#include <string>

#include "telear/core/result.hpp"

namespace telear::vision {

enum class OpenCvStorageFormat { yaml, xml };

// XML when the path ends in ".xml" (any case), else YAML.
OpenCvStorageFormat opencv_storage_format_of_path(const std::string& path);

// True when `text` is XML (its first non-blank character is '<'), as cv::FileStorage decides.
bool is_xml_text(const std::string& text);

// `text` (FileStorage YAML or XML) rewritten in `format`. The error says why OpenCV could not
// read it, e.g. "not valid OpenCV FileStorage XML: <OpenCV's reason>".
Result<std::string> convert_opencv_storage(const std::string& text, OpenCvStorageFormat format);

}  // namespace telear::vision
