#pragma once
// OpenCV's predefined ArUco dictionaries (cv::aruco::PREDEFINED_DICTIONARY_NAME, OpenCV 4.6):
// the one table of their names that the ChArUco calibration patterns
// (telear/vision/charuco_board.hpp) and the registration targets
// (telear/vision/registration_target.hpp) read. Two spellings stand for one dictionary:
//   - calibration patterns keep the canonical short name, lower case without "DICT_"
//     ("4x4_50", "apriltag_36h11"), as in "charuco:7x5:0.04:0.03:4x4_50";
//   - registration targets keep OpenCV's enum name ("DICT_4X4_50", "DICT_APRILTAG_36h11"), as
//     cv::aruco and the mount file write it.
// Both parsers ignore case and an optional "DICT_" prefix.

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace cv::aruco {
class Dictionary;
}

namespace telear::vision {

// The dictionary names a ChArUco calibration pattern accepts: OpenCV's 4x4, 5x5 and 6x6
// dictionaries and AprilTag 36h11, canonical ("4x4_50" .. "6x6_1000", "apriltag_36h11").
const std::vector<std::string>& aruco_dictionary_names();

// The canonical name of `name` (one of the above; case and a "DICT_" prefix are ignored),
// or nullopt for an unknown one.
std::optional<std::string> canonical_aruco_dictionary(const std::string& name);

// OpenCV's name of an ArUco (not AprilTag) dictionary, any of the 17 OpenCV predefines:
// "4x4_50", "dict_4x4_50" -> "DICT_4X4_50"; "" when unknown.
std::string opencv_aruco_dictionary(const std::string& name);

// OpenCV's name of an AprilTag family: "36h11", "tag36h11", "DICT_APRILTAG_36h11" ->
// "DICT_APRILTAG_36h11"; "" when unknown.
std::string opencv_apriltag_family(const std::string& name);

// For error messages: the ArUco dictionaries without "DICT_" ("4X4_50, ..., ARUCO_ORIGINAL")
// and the AprilTag families ("16h5, 25h9, 36h10, 36h11").
std::string opencv_aruco_dictionary_list();
std::string opencv_apriltag_family_list();

// The number of markers in a dictionary (a canonical or an OpenCV name).
int aruco_dictionary_size(const std::string& name);

// cv::aruco::getPredefinedDictionary of a dictionary (a canonical or an OpenCV name).
cv::Ptr<cv::aruco::Dictionary> predefined_aruco_dictionary(const std::string& name);

}  // namespace telear::vision
