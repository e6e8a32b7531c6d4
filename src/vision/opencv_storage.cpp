#include "telear/vision/opencv_storage.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <opencv2/core.hpp>
#include <opencv2/core/persistence.hpp>
#include <string>
#include <vector>

namespace telear::vision {
namespace {

// The largest rows or cols of a matrix in a camera or calibration file (they hold 3x3, 4x4,
// 1x14 matrices).
constexpr long long kMaxMatrixSide = 1024;

// An OpenCV matrix as the readers see it: a map of exactly rows, cols, dt and data. The
// layouts' own markers (YAML's !!opencv-matrix tag, XML's type_id attribute) are not exposed
// by cv::FileNode, so the keys decide.
bool is_matrix(const cv::FileNode& node) {
  if (!node.isMap() || node.size() != 4) return false;
  for (const char* key : {"rows", "cols", "dt", "data"}) {
    if (node[key].empty()) return false;
  }
  return true;
}

void copy_value(cv::FileStorage& out, const cv::FileNode& node);

// Writes the map's entries (the caller opened it).
void copy_entries(cv::FileStorage& out, const cv::FileNode& map) {
  for (cv::FileNodeIterator it = map.begin(); it != map.end(); ++it) {
    const cv::FileNode child = *it;
    out << child.name();
    copy_value(out, child);
  }
}

void copy_value(cv::FileStorage& out, const cv::FileNode& node) {
  if (is_matrix(node)) {
    // A malformed matrix (data not rows x cols) is copied as the map it is, for the reader to
    // say what is wrong with it.
    cv::Mat m;
    try {
      node >> m;
    } catch (const cv::Exception&) {
      m.release();
    }
    if (!m.empty()) {
      out << m;
      return;
    }
  }
  if (node.isMap()) {
    out << "{";
    copy_entries(out, node);
    out << "}";
  } else if (node.isSeq()) {
    out << "[";
    for (cv::FileNodeIterator it = node.begin(); it != node.end(); ++it) copy_value(out, *it);
    out << "]";
  } else if (node.isInt()) {
    out << static_cast<int>(node);
  } else if (node.isReal()) {
    out << static_cast<double>(node);
  } else if (node.isString()) {
    out << static_cast<std::string>(node);
  } else {
    out << "";  // an empty value (YAML's "key:"): kept as an empty string
  }
}

// OpenCV 4.6 puts a parse error's position and reason in the exception's `func`, as
// "(<line>): <reason>" (the file name before it is empty for text in memory); other failures
// are a bare assertion in `err`.
std::string reason_of(const cv::Exception& e) {
  if (e.code == cv::Error::StsParseError && e.func.size() > 1 && e.func.front() == '(') {
    const auto close = e.func.find("): ");
    if (close != std::string::npos) {
      return "line " + e.func.substr(1, close - 1) + ": " + e.func.substr(close + 3);
    }
    return e.func;
  }
  if (e.err == "Unsupported file storage format") {
    return "unsupported layout (OpenCV's XML starts with <?xml version=\"1.0\"?> and "
           "<opencv_storage>)";
  }
  return "malformed (OpenCV: " + e.err + ")";
}

}  // namespace

OpenCvStorageFormat opencv_storage_format_of_path(const std::string& path) {
  if (path.size() < 4) return OpenCvStorageFormat::yaml;
  std::string extension = path.substr(path.size() - 4);
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".xml" ? OpenCvStorageFormat::xml : OpenCvStorageFormat::yaml;
}

bool is_xml_text(const std::string& text) {
  std::size_t i = 0;
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) i = 3;  // UTF-8 byte order mark
  while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
  return i < text.size() && text[i] == '<';
}

Result<std::string> convert_opencv_storage(const std::string& text, OpenCvStorageFormat format) {
  const char* from = is_xml_text(text) ? "XML" : "YAML";
  // OpenCV 4.6's in-memory reader takes the text up to its first NUL byte and then crashes
  // (a null dereference in its XML parser, found by fuzz/camera_file_fuzz.cpp): no text file
  // holds one, so it is refused first.
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos) {
    return Error{std::string("not valid OpenCV FileStorage ") + from + ": a NUL byte at offset " +
                 std::to_string(nul)};
  }
  // OpenCV allocates an opencv-matrix's rows x cols before it reads the data: a file that says
  // `<cols>4294967288</cols>` asked for 17 GB (found by fuzz/camera_file_fuzz.cpp). The
  // matrices of camera and calibration files are small; larger sizes are refused first.
  for (const char* key : {"<rows>", "<cols>", "rows:", "cols:"}) {
    for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1)) {
      std::size_t i = at + std::strlen(key);
      while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
      std::size_t digits = 0;
      long long value = 0;
      while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])) && digits < 10) {
        value = value * 10 + (text[i] - '0');
        ++i;
        ++digits;
      }
      const bool more_digits = i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]));
      // Not a number at all (`<rows>?</rows>`) made OpenCV allocate 48 GB as well.
      if (digits == 0 || more_digits || value > kMaxMatrixSide) {
        return Error{std::string("not valid OpenCV FileStorage ") + from + ": a matrix's " +
                     std::string(key).substr(key[0] == '<' ? 1 : 0, 4) +
                     " is not a number from 0 to " + std::to_string(kMaxMatrixSide)};
      }
    }
  }
  try {
    cv::FileStorage in(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
    if (!in.isOpened()) {
      return Error{std::string("not valid OpenCV FileStorage ") + from + ": OpenCV cannot read it"};
    }
    const cv::FileNode root = in.root();
    if (!root.isMap()) {
      return Error{std::string("not valid OpenCV FileStorage ") + from +
                   ": the top level must be a map of keys"};
    }
    cv::FileStorage out(format == OpenCvStorageFormat::xml ? ".xml" : ".yaml",
                        cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
    copy_entries(out, root);
    return out.releaseAndGetString();
  } catch (const cv::Exception& e) {
    return Error{std::string("not valid OpenCV FileStorage ") + from + ": " + reason_of(e)};
  }
}

}  // namespace telear::vision
