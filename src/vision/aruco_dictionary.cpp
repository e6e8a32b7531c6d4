#include "telear/vision/aruco_dictionary.hpp"

#include <cassert>
#include <cctype>
#include <opencv2/aruco.hpp>

#include "vision_text.hpp"

namespace telear::vision {
namespace {

struct DictionaryName {
  const char* name;  // OpenCV's enum name
  cv::aruco::PREDEFINED_DICTIONARY_NAME id;
  bool calibration;  // offered for ChArUco calibration patterns
};

constexpr std::size_t kAprilTagPrefix = 14;  // "DICT_APRILTAG_"

// In OpenCV's enum order: the ArUco dictionaries, then the AprilTag families.
constexpr DictionaryName kDictionaries[] = {
    {"DICT_4X4_50", cv::aruco::DICT_4X4_50, true},
    {"DICT_4X4_100", cv::aruco::DICT_4X4_100, true},
    {"DICT_4X4_250", cv::aruco::DICT_4X4_250, true},
    {"DICT_4X4_1000", cv::aruco::DICT_4X4_1000, true},
    {"DICT_5X5_50", cv::aruco::DICT_5X5_50, true},
    {"DICT_5X5_100", cv::aruco::DICT_5X5_100, true},
    {"DICT_5X5_250", cv::aruco::DICT_5X5_250, true},
    {"DICT_5X5_1000", cv::aruco::DICT_5X5_1000, true},
    {"DICT_6X6_50", cv::aruco::DICT_6X6_50, true},
    {"DICT_6X6_100", cv::aruco::DICT_6X6_100, true},
    {"DICT_6X6_250", cv::aruco::DICT_6X6_250, true},
    {"DICT_6X6_1000", cv::aruco::DICT_6X6_1000, true},
    {"DICT_7X7_50", cv::aruco::DICT_7X7_50, false},
    {"DICT_7X7_100", cv::aruco::DICT_7X7_100, false},
    {"DICT_7X7_250", cv::aruco::DICT_7X7_250, false},
    {"DICT_7X7_1000", cv::aruco::DICT_7X7_1000, false},
    {"DICT_ARUCO_ORIGINAL", cv::aruco::DICT_ARUCO_ORIGINAL, false},
    {"DICT_APRILTAG_16h5", cv::aruco::DICT_APRILTAG_16h5, false},
    {"DICT_APRILTAG_25h9", cv::aruco::DICT_APRILTAG_25h9, false},
    {"DICT_APRILTAG_36h10", cv::aruco::DICT_APRILTAG_36h10, false},
    {"DICT_APRILTAG_36h11", cv::aruco::DICT_APRILTAG_36h11, true},
};

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

bool is_apriltag(const DictionaryName& d) {
  return std::string(d.name).rfind("DICT_APRILTAG_", 0) == 0;
}

// The entry of a name in either spelling (case ignored, "DICT_" optional); nullptr if none.
const DictionaryName* find(const std::string& text) {
  std::string name = upper(text);
  if (name.rfind("DICT_", 0) != 0) name = "DICT_" + name;
  for (const DictionaryName& d : kDictionaries) {
    if (name == upper(d.name)) return &d;
  }
  return nullptr;
}

const DictionaryName& entry_of(const std::string& name) {
  const DictionaryName* d = find(name);
  assert(d != nullptr && "not a dictionary name");
  return d != nullptr ? *d : kDictionaries[0];
}

std::string list_names(bool apriltag, std::size_t skip) {
  std::string out;
  for (const DictionaryName& d : kDictionaries) {
    if (is_apriltag(d) != apriltag) continue;
    if (!out.empty()) out += ", ";
    out += std::string(d.name).substr(skip);
  }
  return out;
}

}  // namespace

const std::vector<std::string>& aruco_dictionary_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> list;
    for (const DictionaryName& d : kDictionaries) {
      if (d.calibration) list.push_back(lower(std::string(d.name).substr(5)));
    }
    return list;
  }();
  return names;
}

std::optional<std::string> canonical_aruco_dictionary(const std::string& name) {
  const DictionaryName* d = find(name);
  if (d == nullptr || !d->calibration) return std::nullopt;
  return lower(std::string(d->name).substr(5));
}

std::string opencv_aruco_dictionary(const std::string& name) {
  const DictionaryName* d = find(name);
  return d != nullptr && !is_apriltag(*d) ? d->name : "";
}

std::string opencv_apriltag_family(const std::string& name) {
  std::string family = upper(name);
  for (const char* prefix : {"DICT_APRILTAG_", "TAG"}) {
    if (family.rfind(prefix, 0) == 0) family = family.substr(std::string(prefix).size());
  }
  const DictionaryName* d = find("DICT_APRILTAG_" + family);
  return d != nullptr ? d->name : "";
}

std::string opencv_aruco_dictionary_list() {
  return list_names(false, 5);
}

std::string opencv_apriltag_family_list() {
  return list_names(true, kAprilTagPrefix);
}

int aruco_dictionary_size(const std::string& name) {
  return predefined_aruco_dictionary(name)->bytesList.rows;
}

cv::Ptr<cv::aruco::Dictionary> predefined_aruco_dictionary(const std::string& name) {
  return cv::aruco::getPredefinedDictionary(entry_of(name).id);
}

}  // namespace telear::vision
