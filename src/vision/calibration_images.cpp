#include "telear/vision/calibration_images.hpp"

#include <glob.h>

#include <algorithm>
#include <map>

#include "telear/core/image_size.hpp"
#include "telear/vision/image_file.hpp"

namespace telear::vision {
namespace {

// One decoded image and its detection; `problem` is empty when the pattern was found;
// `fatal` stops the whole run (the pattern does not describe the board).
struct ImageResult {
  std::vector<cv::Point2f> points;
  std::vector<int> ids;  // each point's index in pattern_object_points()
  std::string problem;
  std::string fatal;
};

// A chessboard pattern smaller than the board is found on part of it (calibration_pattern.hpp):
// the first two images where it is found are checked for a larger board.
struct SizeCheck {
  int remaining = 2;
};

ImageResult process_image(const std::string& path, const CalibrationPattern& pattern,
                          cv::Size& image_size, SizeCheck& size_check) {
  auto read = read_image_file(path, ImageFileMode::kGrey);
  const cv::Mat image = read ? *read : cv::Mat();
  if (image.empty()) {
    return {{}, {}, "cannot decode image (corrupt or not an image file); replace or delete it", {}};
  }
  if (image_size.empty()) {
    image_size = image.size();
  } else if (image.size() != image_size) {
    return {{},
            {},
            "image is " + core::to_string(core::ImageSize{image.cols, image.rows}) +
                " but the first image is " +
                core::to_string(core::ImageSize{image_size.width, image_size.height}) +
                "; use images from one camera at one resolution",
            {}};
  }
  auto points = detect_pattern_points(image, pattern);
  if (!points) return {{}, {}, points.error().message, {}};
  if (pattern.kind == PatternKind::kChessboard && size_check.remaining > 0) {
    --size_check.remaining;
    if (const auto board = larger_chessboard(image, pattern)) {
      CalibrationPattern right = pattern;
      right.cols = board->width;
      right.rows = board->height;
      return {{},
              {},
              {},
              "the pattern " + pattern.spec() + " is smaller than the board in '" +
                  file_name_of(path) + "', which has " + std::to_string(board->width) + "x" +
                  std::to_string(board->height) + " inner corners; calibrate with " + right.spec()};
    }
  }
  return {std::move(points->image_points), std::move(points->ids), {}, {}};
}

// Partial views (ChArUco): the object points of the corners seen; empty for a whole pattern,
// which the calibration takes as pattern_object_points().
std::vector<cv::Point3f> view_object_points(const CalibrationPattern& pattern,
                                            const std::vector<int>& ids) {
  if (pattern.kind != PatternKind::kCharuco) return {};
  return pattern_object_points(pattern, ids);
}

// A stereo pair of ChArUco views keeps the corners both images show (by id), in left order.
// Returns the number of common corners.
std::size_t keep_common_corners(ImageResult& left, ImageResult& right) {
  std::map<int, cv::Point2f> right_by_id;
  for (std::size_t k = 0; k < right.ids.size(); ++k) right_by_id[right.ids[k]] = right.points[k];
  ImageResult l, r;
  for (std::size_t k = 0; k < left.ids.size(); ++k) {
    const auto found = right_by_id.find(left.ids[k]);
    if (found == right_by_id.end()) continue;
    l.points.push_back(left.points[k]);
    l.ids.push_back(left.ids[k]);
    r.points.push_back(found->second);
    r.ids.push_back(left.ids[k]);
  }
  left.points = std::move(l.points);
  left.ids = std::move(l.ids);
  right.points = std::move(r.points);
  right.ids = std::move(r.ids);
  return left.ids.size();
}

// Reverses `right` when its first-to-last direction opposes the left's (header comment).
bool align_chessboard_order(const std::vector<cv::Point2f>& left, std::vector<cv::Point2f>& right) {
  const cv::Point2f dl = left.back() - left.front();
  const cv::Point2f dr = right.back() - right.front();
  if (dl.dot(dr) >= 0.0f) return false;
  std::reverse(right.begin(), right.end());
  return true;
}

}  // namespace

std::string file_name_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

Result<std::vector<std::string>> expand_image_glob(const std::string& pattern,
                                                   const std::string& option) {
  glob_t matches{};
  const int status = ::glob(pattern.c_str(), GLOB_ERR, nullptr, &matches);
  std::vector<std::string> paths;
  if (status == 0) {
    for (std::size_t i = 0; i < matches.gl_pathc; ++i) paths.emplace_back(matches.gl_pathv[i]);
  }
  ::globfree(&matches);
  if (status == GLOB_NOSPACE) return Error{option + " '" + pattern + "': out of memory"};
  if (status == GLOB_ABORTED) {
    return Error{option + " '" + pattern + "': cannot read the directory; check its permissions"};
  }
  if (paths.empty()) {
    return Error{option + " '" + pattern +
                 "' matches no file; check the directory and the pattern, and quote it so "
                 "that telear expands it (e.g. 'images/left*.png')"};
  }
  std::sort(paths.begin(), paths.end());
  return paths;
}

Result<MonoImageViews> detect_in_images(const std::vector<std::string>& paths,
                                        const CalibrationPattern& pattern,
                                        const DetectionCallback& progress) {
  if (paths.empty()) return Error{"no images given"};
  MonoImageViews result;
  SizeCheck size_check;
  bool any_decoded = false;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    ImageResult image = process_image(paths[i], pattern, result.image_size, size_check);
    if (!image.fatal.empty()) return Error{image.fatal};
    any_decoded = any_decoded || !result.image_size.empty();
    const bool found = image.problem.empty();
    if (found) {
      result.views.push_back(
          {paths[i], std::move(image.points), view_object_points(pattern, image.ids)});
    } else {
      result.rejected.push_back({.name = paths[i], .right_name = {}, .reason = image.problem});
    }
    if (progress) {
      progress(
          {i + 1, paths.size(), file_name_of(paths[i]), found, found ? "found" : image.problem});
    }
  }
  if (!any_decoded) {
    return Error{"none of the " + std::to_string(paths.size()) +
                 " images could be decoded; check that the files are PNG or JPEG images"};
  }
  return result;
}

Result<StereoImageViews> detect_in_image_pairs(const std::vector<std::string>& left_paths,
                                               const std::vector<std::string>& right_paths,
                                               const CalibrationPattern& pattern,
                                               const DetectionCallback& progress) {
  if (left_paths.empty() || right_paths.empty()) return Error{"no images given"};
  if (left_paths.size() != right_paths.size()) {
    return Error{std::to_string(left_paths.size()) + " left images but " +
                 std::to_string(right_paths.size()) + " right images" +
                 "; every left image needs the right image taken at the same moment (pairs "
                 "are matched in sorted name order): remove the unpaired images"};
  }
  StereoImageViews result;
  SizeCheck size_check;
  for (std::size_t i = 0; i < left_paths.size(); ++i) {
    const std::string name = file_name_of(left_paths[i]) + " + " + file_name_of(right_paths[i]);
    ImageResult left = process_image(left_paths[i], pattern, result.image_size, size_check);
    if (!left.fatal.empty()) return Error{left.fatal};
    ImageResult right = process_image(right_paths[i], pattern, result.image_size, size_check);
    if (!right.fatal.empty()) return Error{right.fatal};
    std::string problem;
    if (!left.problem.empty() && left.problem == right.problem) {
      problem = "left and right: " + left.problem;
    } else {
      if (!left.problem.empty()) problem = "left: " + left.problem;
      if (!right.problem.empty()) {
        problem += (problem.empty() ? "" : "; ") + ("right: " + right.problem);
      }
    }
    if (problem.empty() && pattern.kind == PatternKind::kCharuco) {
      const std::size_t seen_left = left.ids.size(), seen_right = right.ids.size();
      const std::size_t common = keep_common_corners(left, right);
      if (static_cast<int>(common) < kMinCharucoCorners) {
        problem = "the images share only " + std::to_string(common) + " ChArUco corners (left " +
                  std::to_string(seen_left) + ", right " + std::to_string(seen_right) +
                  "), fewer than the " + std::to_string(kMinCharucoCorners) + " a pair needs";
      }
    }
    const bool found = problem.empty();
    if (found) {
      if (pattern.kind == PatternKind::kChessboard &&
          align_chessboard_order(left.points, right.points)) {
        ++result.reordered_pairs;
      }
      result.views.push_back({left_paths[i], right_paths[i], std::move(left.points),
                              std::move(right.points), view_object_points(pattern, left.ids)});
    } else {
      result.rejected.push_back(
          {.name = left_paths[i], .right_name = right_paths[i], .reason = problem});
    }
    if (progress) progress({i + 1, left_paths.size(), name, found, found ? "found" : problem});
  }
  if (result.image_size.empty()) {
    return Error{"none of the " + std::to_string(2 * left_paths.size()) +
                 " images could be decoded; check that the files are PNG or JPEG images"};
  }
  return result;
}

}  // namespace telear::vision
