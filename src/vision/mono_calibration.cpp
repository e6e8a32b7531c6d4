#include "telear/vision/mono_calibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/calib3d.hpp>

#include "telear/core/image_size.hpp"
#include "telear/core/number_format.hpp"
#include "telear/vision/opencv_camera.hpp"
#include "telear/vision/opencv_pose.hpp"
#include "telear/vision/projection_jacobian.hpp"

namespace telear::vision {
namespace {

// One solve's output in the form both solvers' results are turned into.
struct Solve {
  double rms = 0.0;
  cv::Mat K, dist;
  std::vector<cv::Mat> rvecs, tvecs;
  std::vector<double> view_errors;                    // rms of each view, pixels
  std::vector<double> intrinsics_std;                 // fx fy cx cy D..., 0 when fixed
  std::vector<Eigen::Matrix<double, 6, 1>> pose_std;  // rvec, tvec per view
};

// cv::fisheye::calibrate returns neither standard deviations nor per-view errors: both come
// from the Gauss-Newton covariance sigma^2 (J^T J)^-1 of the problem it solved (free
// intrinsics and every view's pose), J from cv::fisheye::projectPoints.
void fisheye_uncertainty(const std::vector<std::vector<cv::Point3f>>& object_points,
                         const std::vector<std::vector<cv::Point2f>>& image_points,
                         const std::vector<int>& free, Solve& s) {
  const auto views = static_cast<Eigen::Index>(image_points.size());
  const auto n_free = static_cast<Eigen::Index>(free.size());
  const Eigen::Index parameters = n_free + 6 * views;
  Eigen::Index rows = 0;  // views may show different numbers of points (partial views)
  for (const auto& object : object_points) rows += static_cast<Eigen::Index>(2 * object.size());
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(rows, parameters);
  double sum_squares = 0.0;
  s.view_errors.clear();
  Eigen::Index row = 0;
  for (Eigen::Index i = 0; i < views; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const std::vector<cv::Point3f>& object = object_points[k];
    const auto rows_of_view = static_cast<Eigen::Index>(2 * object.size());
    const ViewProjection p = project_view(object, image_points[k], s.rvecs[k], s.tvecs[k], s.K,
                                          s.dist, DistortionModel::equidistant);
    for (Eigen::Index f = 0; f < n_free; ++f) {
      J.block(row, f, rows_of_view, 1) = p.d_intrinsics.col(free[static_cast<std::size_t>(f)]);
    }
    J.block(row, n_free + 6 * i, rows_of_view, 6) = p.d_pose;
    row += rows_of_view;
    sum_squares += p.residual.squaredNorm();
    s.view_errors.push_back(
        std::sqrt(p.residual.squaredNorm() / static_cast<double>(object.size())));
  }
  const double total_points = static_cast<double>(rows) / 2.0;
  s.rms = std::sqrt(sum_squares / total_points);
  const double sigma2 = sum_squares / static_cast<double>(J.rows() - parameters);
  const Eigen::MatrixXd covariance =
      sigma2 * (J.transpose() * J).ldlt().solve(Eigen::MatrixXd::Identity(parameters, parameters));
  const Eigen::VectorXd sd = covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  s.intrinsics_std.assign(
      static_cast<std::size_t>(intrinsic_parameter_count(DistortionModel::equidistant)), 0.0);
  for (Eigen::Index f = 0; f < n_free; ++f)
    s.intrinsics_std[static_cast<std::size_t>(free[static_cast<std::size_t>(f)])] = sd(f);
  s.pose_std.clear();
  for (Eigen::Index i = 0; i < views; ++i) s.pose_std.push_back(sd.segment<6>(n_free + 6 * i));
}

Result<Solve> solve(const std::vector<std::vector<cv::Point3f>>& object_points,
                    const std::vector<std::vector<cv::Point2f>>& image_points, cv::Size image_size,
                    const CalibrationOptions& options) {
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS,
                                  options.max_iterations, DBL_EPSILON);
  Solve s;
  try {
    if (options.model == DistortionModel::equidistant) {
      cv::Matx33d K;
      cv::Vec4d D;
      s.rms = cv::fisheye::calibrate(object_points, image_points, image_size, K, D, s.rvecs,
                                     s.tvecs, calibration_flags(options), criteria);
      s.K = cv::Mat(K, true);
      s.dist = cv::Mat(D, true).reshape(1, 1);
    } else {
      cv::Mat std_intrinsics, std_extrinsics, per_view;
      s.rms = cv::calibrateCamera(object_points, image_points, image_size, s.K, s.dist, s.rvecs,
                                  s.tvecs, std_intrinsics, std_extrinsics, per_view,
                                  calibration_flags(options), criteria);
      if (!std::isfinite(s.rms) || !cv::checkRange(s.K) || !cv::checkRange(s.dist)) return s;
      // OpenCV returns 5 (plumb_bob) or 8 (rational) coefficients with the model's flags.
      const int count = static_cast<int>(distortion_coefficient_count(options.model));
      s.dist = s.dist.reshape(1, 1).colRange(0, count).clone();
      for (int i = 0; i < 4 + count; ++i) s.intrinsics_std.push_back(std_intrinsics.at<double>(i));
      for (std::size_t k = 0; k < image_points.size(); ++k) {
        s.view_errors.push_back(per_view.at<double>(static_cast<int>(k)));
        Eigen::Matrix<double, 6, 1> pose;
        for (int i = 0; i < 6; ++i)
          pose(i) = std_extrinsics.at<double>(static_cast<int>(6 * k) + i);
        s.pose_std.push_back(pose);
      }
      return s;
    }
  } catch (const cv::Exception& e) {
    return Error{"calibration failed (" + e.msg +
                 "); the views are probably degenerate: use views tilted in different "
                 "directions, not all parallel to the image plane"};
  }
  for (cv::Mat& m : s.rvecs) m.convertTo(m, CV_64F);
  for (cv::Mat& m : s.tvecs) m.convertTo(m, CV_64F);
  if (std::isfinite(s.rms) && cv::checkRange(s.K) && cv::checkRange(s.dist)) {
    fisheye_uncertainty(object_points, image_points, free_intrinsic_parameters(options), s);
  }
  return s;
}

}  // namespace

Status CalibrationOptions::validate() const {
  if (!(outlier_factor == 0.0 || (std::isfinite(outlier_factor) && outlier_factor > 1.0))) {
    return Error{"outlier_factor must be 0 (keep every view) or a finite number > 1"};
  }
  if (!std::isfinite(outlier_floor_px) || outlier_floor_px < 0.0) {
    return Error{"outlier_floor_px must be a finite number >= 0"};
  }
  if (min_views < 3) return Error{"min_views must be at least 3"};
  if (zero_tangential && model == DistortionModel::equidistant) {
    return Error{"zero_tangential: the equidistant (fisheye) model has no tangential terms"};
  }
  if (max_iterations < 1) return Error{"max_iterations must be at least 1"};
  return Status::Ok();
}

int calibration_flags(const CalibrationOptions& options) {
  if (options.model == DistortionModel::equidistant) {
    // The poses are re-solved after each intrinsics update (OpenCV's fisheye sample does the
    // same; without it the solve often stalls far from the minimum); skew is not estimated,
    // as for the other models.
    return cv::fisheye::CALIB_RECOMPUTE_EXTRINSIC | cv::fisheye::CALIB_FIX_SKEW;
  }
  int flags = 0;
  if (options.model == DistortionModel::rational_polynomial) {
    flags |= cv::CALIB_RATIONAL_MODEL;
  } else if (options.fix_k3) {
    flags |= cv::CALIB_FIX_K3;
  }
  if (options.zero_tangential) flags |= cv::CALIB_ZERO_TANGENT_DIST;
  return flags;
}

std::vector<int> free_intrinsic_parameters(const CalibrationOptions& options) {
  std::vector<int> free;
  for (int i = 0; i < intrinsic_parameter_count(options.model); ++i) {
    const bool tangential = options.model != DistortionModel::equidistant && (i == 6 || i == 7);
    if (options.zero_tangential && tangential) continue;
    if (options.model == DistortionModel::plumb_bob && options.fix_k3 && i == 8) continue;
    free.push_back(i);
  }
  return free;
}

IntrinsicsStdDev intrinsics_std_dev(const std::vector<double>& full, DistortionModel model) {
  assert(static_cast<int>(full.size()) == intrinsic_parameter_count(model));
  IntrinsicsStdDev sd{full[0], full[1], full[2], full[3], {}};
  sd.kc = Distortion::from_coefficients(model, std::vector<double>(full.begin() + 4, full.end()))
              .value();
  return sd;
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
    return Error{"image size " +
                 core::to_string(core::ImageSize{image_size.width, image_size.height}) +
                 " is not positive"};
  }
  for (const PatternView& view : views) {
    if (!view.object_points.empty()) {
      // Part of the pattern (a ChArUco board partly out of frame): its own object points.
      if (view.object_points.size() != view.image_points.size()) {
        return Error{"view '" + view.name + "' has " + std::to_string(view.image_points.size()) +
                     " image points but " + std::to_string(view.object_points.size()) +
                     " object points"};
      }
      if (view.image_points.size() < 4) {
        return Error{"view '" + view.name + "' has " + std::to_string(view.image_points.size()) +
                     " points; a view needs at least 4"};
      }
    } else if (static_cast<int>(view.image_points.size()) != pattern.point_count()) {
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
    std::vector<std::vector<cv::Point2f>> image_points;
    std::vector<std::vector<cv::Point3f>> object_points;
    for (std::size_t i : active) {
      image_points.push_back(views[i].image_points);
      object_points.push_back(views[i].object_points.empty() ? object : views[i].object_points);
    }

    auto solved = solve(object_points, image_points, image_size, options);
    if (!solved) return solved.error();
    const Solve& sol = *solved;
    if (!std::isfinite(sol.rms) || !cv::checkRange(sol.K) || !cv::checkRange(sol.dist)) {
      return Error{"calibration diverged; use views tilted in different directions"};
    }

    const std::vector<double>& errors = sol.view_errors;
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
    camera.fx = sol.K.at<double>(0, 0);
    camera.fy = sol.K.at<double>(1, 1);
    camera.cx = sol.K.at<double>(0, 2);
    camera.cy = sol.K.at<double>(1, 2);
    camera.alpha_c = 0.0;
    camera.kc = Distortion::from_coefficients(options.model, std::vector<double>(sol.dist)).value();
    result.std_dev = intrinsics_std_dev(sol.intrinsics_std, options.model);
    result.rms_px = sol.rms;
    for (std::size_t k = 0; k < active.size(); ++k) {
      CalibratedView view;
      view.name = views[active[k]].name;
      view.rms_px = errors[k];
      view.T_cam_target = pose_from_rvec_tvec(sol.rvecs[k], sol.tvecs[k]);
      view.rotation_std = sol.pose_std[k].head<3>();
      view.translation_std = sol.pose_std[k].tail<3>();
      result.views.push_back(std::move(view));
    }
    return result;
  }
}

}  // namespace telear::vision
