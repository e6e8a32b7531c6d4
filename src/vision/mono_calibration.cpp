#include "telear/vision/mono_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/calib3d.hpp>

#include "telear/core/number_format.hpp"
#include "telear/vision/opencv_pose.hpp"

namespace telear::vision {
namespace {}  // namespace

Status CalibrationOptions::validate() const {
  if (!(outlier_factor == 0.0 || (std::isfinite(outlier_factor) && outlier_factor > 1.0))) {
    return Error{"outlier_factor must be 0 (keep every view) or a finite number > 1"};
  }
  if (!std::isfinite(outlier_floor_px) || outlier_floor_px < 0.0) {
    return Error{"outlier_floor_px must be a finite number >= 0"};
  }
  if (min_views < 3) return Error{"min_views must be at least 3"};
  if (max_iterations < 1) return Error{"max_iterations must be at least 1"};
  return Status::Ok();
}

int calibration_flags(const CalibrationOptions& options) {
  int flags = 0;
  if (options.fix_k3) flags |= cv::CALIB_FIX_K3;
  if (options.zero_tangential) flags |= cv::CALIB_ZERO_TANGENT_DIST;
  return flags;
}

double median_of(std::vector<double> values) {
  assert(!values.empty());
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  if (values.size() % 2 == 1) return *middle;
  return 0.5 * (*middle + *std::max_element(values.begin(), middle));
}

std::string too_few_views_message(std::size_t usable, int needed, const std::string& what) {
  return "too few views: " + std::to_string(usable) + " usable " + what + " (need at least " +
         std::to_string(needed) +
         "); capture more images that show the whole pattern, tilted in different directions "
         "and covering the image corners";
}

Status check_views(const std::vector<PatternView>& views, const CalibrationPattern& pattern,
                   cv::Size image_size) {
  if (image_size.width <= 0 || image_size.height <= 0) {
    return Error{"image size " + std::to_string(image_size.width) + "x" +
                 std::to_string(image_size.height) + " is not positive"};
  }
  for (const PatternView& view : views) {
    if (static_cast<int>(view.image_points.size()) != pattern.point_count()) {
      return Error{"view '" + view.name + "' has " + std::to_string(view.image_points.size()) +
                   " points but pattern " + pattern.spec() + " has " +
                   std::to_string(pattern.point_count())};
    }
    for (const cv::Point2f& p : view.image_points) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
        return Error{"view '" + view.name + "' has a non-finite image point"};
      }
    }
  }
  return Status::Ok();
}

Result<MonoCalibration> calibrate_mono(const CalibrationPattern& pattern,
                                       const std::vector<PatternView>& views, cv::Size image_size,
                                       const CalibrationOptions& options) {
  if (Status s = options.validate(); !s) return Error{"calibration options: " + s.error().message};
  if (Status s = check_views(views, pattern, image_size); !s) return s.error();
  if (static_cast<int>(views.size()) < options.min_views) {
    return Error{too_few_views_message(views.size(), options.min_views, "views")};
  }

  const std::vector<cv::Point3f> object = pattern_object_points(pattern);
  std::vector<std::size_t> active(views.size());
  for (std::size_t i = 0; i < views.size(); ++i) active[i] = i;

  MonoCalibration result;
  while (true) {
    std::vector<std::vector<cv::Point3f>> object_points(active.size(), object);
    std::vector<std::vector<cv::Point2f>> image_points;
    for (std::size_t i : active) image_points.push_back(views[i].image_points);

    cv::Mat K, dist, std_intrinsics, std_extrinsics, per_view;
    std::vector<cv::Mat> rvecs, tvecs;
    double rms = 0.0;
    try {
      rms =
          cv::calibrateCamera(object_points, image_points, image_size, K, dist, rvecs, tvecs,
                              std_intrinsics, std_extrinsics, per_view, calibration_flags(options),
                              cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS,
                                               options.max_iterations, DBL_EPSILON));
    } catch (const cv::Exception& e) {
      return Error{"calibration failed (" + e.msg +
                   "); the views are probably degenerate: use views tilted in different "
                   "directions, not all parallel to the image plane"};
    }
    if (!std::isfinite(rms) || !cv::checkRange(K) || !cv::checkRange(dist)) {
      return Error{"calibration diverged; use views tilted in different directions"};
    }

    std::vector<double> errors(active.size());
    for (std::size_t k = 0; k < active.size(); ++k)
      errors[k] = per_view.at<double>(static_cast<int>(k));
    const double median = median_of(errors);
    const auto worst =
        static_cast<std::size_t>(std::max_element(errors.begin(), errors.end()) - errors.begin());
    if (options.outlier_factor > 0.0 && errors[worst] > options.outlier_factor * median &&
        errors[worst] > options.outlier_floor_px &&
        static_cast<int>(active.size()) > options.min_views) {
      char factor[16];
      std::snprintf(factor, sizeof factor, "%g", options.outlier_factor);
      result.rejected.push_back(
          {.name = views[active[worst]].name,
           .right_name = {},
           .reason = "outlier: reprojection RMS " + core::format_fixed(errors[worst], 3, "px") +
                     " > " + factor + " x median " + core::format_fixed(median, 3, "px")});
      active.erase(active.begin() + static_cast<std::ptrdiff_t>(worst));
      continue;
    }

    CameraModel& camera = result.camera;
    camera.width = image_size.width;
    camera.height = image_size.height;
    camera.fx = K.at<double>(0, 0);
    camera.fy = K.at<double>(1, 1);
    camera.cx = K.at<double>(0, 2);
    camera.cy = K.at<double>(1, 2);
    camera.alpha_c = 0.0;
    const auto d = [&dist](int i) {
      return i < static_cast<int>(dist.total()) ? dist.at<double>(i) : 0.0;
    };
    camera.kc = Distortion::plumb_bob(d(0), d(1), d(2), d(3), d(4));
    const auto s = [&std_intrinsics](int i) { return std_intrinsics.at<double>(i); };
    result.std_dev = {s(0), s(1), s(2), s(3), Distortion::plumb_bob(s(4), s(5), s(6), s(7), s(8))};
    result.rms_px = rms;
    for (std::size_t k = 0; k < active.size(); ++k) {
      CalibratedView view;
      view.name = views[active[k]].name;
      view.rms_px = errors[k];
      view.T_cam_target = pose_from_rvec_tvec(rvecs[k], tvecs[k]);
      const int row = static_cast<int>(6 * k);
      for (int i = 0; i < 3; ++i) {
        view.rotation_std(i) = std_extrinsics.at<double>(row + i);
        view.translation_std(i) = std_extrinsics.at<double>(row + 3 + i);
      }
      result.views.push_back(std::move(view));
    }
    return result;
  }
}

}  // namespace telear::vision
