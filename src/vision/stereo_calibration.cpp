#include "telear/vision/stereo_calibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/calib3d.hpp>

#include "telear/core/number_format.hpp"
#include "telear/vision/opencv_camera.hpp"
#include "telear/vision/opencv_pose.hpp"
#include "telear/vision/projection_jacobian.hpp"

namespace telear::vision {
namespace {

cv::Mat camera_matrix(const CameraModel& camera) {
  return (cv::Mat_<double>(3, 3) << camera.fx, 0.0, camera.cx, 0.0, camera.fy, camera.cy, 0.0, 0.0,
          1.0);
}

cv::Mat distortion_vector(const CameraModel& camera) {
  return opencv_distortion(camera.kc);
}

CameraModel camera_from(const cv::Mat& K, const cv::Mat& dist, cv::Size size,
                        DistortionModel model) {
  CameraModel camera;
  camera.width = size.width;
  camera.height = size.height;
  camera.fx = K.at<double>(0, 0);
  camera.fy = K.at<double>(1, 1);
  camera.cx = K.at<double>(0, 2);
  camera.cy = K.at<double>(1, 2);
  camera.kc = Distortion::from_coefficients(model, std::vector<double>(dist.reshape(1, 1))).value();
  return camera;
}

// [SECTION] Covariance of the joint stereo problem
//
// Parameters, in this order: the free intrinsics of the left camera, those of the right
// camera (none when the intrinsics are held fixed), the rotation vector om of R, T, and for
// each view the left pose (rotation vector r_i, translation t_i). Residuals: for each view,
// the 2 P left components, then the 2 P right components. The right pose of view i is
// compose((r_i, t_i), (om, T)): R_Ri = R R_i, t_Ri = R t_i + T (cv::composeRT).

// The intrinsics (fx fy cx cy, then the model's D vector) that the options leave free.
std::vector<int> free_intrinsics(const StereoCalibrationOptions& options) {
  if (!options.refine_intrinsics) return {};
  return free_intrinsic_parameters(options.calibration);
}

struct ViewPose {
  cv::Mat rvec, tvec;  // 3x1 double
};

struct RightPose {
  cv::Mat rvec, tvec;
  Eigen::MatrixXd d_left_pose;  // 6x6: d(rR, tR) / d(r_i, t_i)
  Eigen::MatrixXd d_stereo;     // 6x6: d(rR, tR) / d(om, T)
};

RightPose compose_right(const ViewPose& left, const cv::Mat& om, const cv::Mat& T) {
  RightPose right;
  cv::Mat dr3dr1, dr3dt1, dr3dr2, dr3dt2, dt3dr1, dt3dt1, dt3dr2, dt3dt2;
  cv::composeRT(left.rvec, left.tvec, om, T, right.rvec, right.tvec, dr3dr1, dr3dt1, dr3dr2, dr3dt2,
                dt3dr1, dt3dt1, dt3dr2, dt3dt2);
  right.d_left_pose.resize(6, 6);
  right.d_left_pose << eigen_from_mat(dr3dr1), eigen_from_mat(dr3dt1), eigen_from_mat(dt3dr1),
      eigen_from_mat(dt3dt1);
  right.d_stereo.resize(6, 6);
  right.d_stereo << eigen_from_mat(dr3dr2), eigen_from_mat(dr3dt2), eigen_from_mat(dt3dr2),
      eigen_from_mat(dt3dt2);
  return right;
}

struct JointSolution {
  DistortionModel model = DistortionModel::plumb_bob;
  cv::Mat K[2], dist[2], om, T;
  std::vector<ViewPose> poses;
};

// The left pose of each view that minimises both images' reprojection error for the given
// intrinsics, R and T (stereoCalibrate does not return its poses): solvePnP on the left
// image, then Gauss-Newton over the 6 pose parameters with both images.
// The object points of a view: its own (part of the pattern, e.g. a ChArUco board partly out
// of frame) or, when it has none, the whole pattern's.
const std::vector<cv::Point3f>& object_of(const StereoPatternView& view,
                                          const std::vector<cv::Point3f>& pattern_points) {
  return view.object_points.empty() ? pattern_points : view.object_points;
}

void solve_left_poses(const std::vector<cv::Point3f>& pattern_points,
                      const std::vector<StereoPatternView>& views, JointSolution& s) {
  s.poses.clear();
  for (const StereoPatternView& view : views) {
    const std::vector<cv::Point3f>& object = object_of(view, pattern_points);
    ViewPose pose;
    solve_view_pose(object, view.left_points, s.K[0], s.dist[0], s.model, pose.rvec, pose.tvec);
    for (int iteration = 0; iteration < 20; ++iteration) {
      const ViewProjection left =
          project_view(object, view.left_points, pose.rvec, pose.tvec, s.K[0], s.dist[0], s.model);
      const RightPose rp = compose_right(pose, s.om, s.T);
      const ViewProjection right =
          project_view(object, view.right_points, rp.rvec, rp.tvec, s.K[1], s.dist[1], s.model);
      Eigen::MatrixXd J(left.residual.size() + right.residual.size(), 6);
      J << left.d_pose, right.d_pose * rp.d_left_pose;
      Eigen::VectorXd r(J.rows());
      r << left.residual, right.residual;
      const Eigen::VectorXd step = (J.transpose() * J).ldlt().solve(-J.transpose() * r);
      for (int i = 0; i < 3; ++i) {
        pose.rvec.at<double>(i) += step(i);
        pose.tvec.at<double>(i) += step(3 + i);
      }
      if (step.norm() < 1e-12) break;
    }
    s.poses.push_back(pose);
  }
}

struct Covariance {
  IntrinsicsStdDev intrinsics[2];
  Eigen::Vector3d rotation_std, translation_std;
  double baseline_std = 0.0;
  double sum_squares[2] = {0.0, 0.0};  // per camera
  std::size_t points = 0;              // per camera
};

Covariance joint_covariance(const std::vector<cv::Point3f>& pattern_points,
                            const std::vector<StereoPatternView>& views, const JointSolution& s,
                            const std::vector<int>& free) {
  const auto n_free = static_cast<Eigen::Index>(free.size());
  const Eigen::Index stereo_col = 2 * n_free;
  const Eigen::Index parameters = stereo_col + 6 + 6 * static_cast<Eigen::Index>(views.size());
  Covariance result;
  for (const StereoPatternView& view : views) {
    result.points += object_of(view, pattern_points).size();
  }
  const auto rows = static_cast<Eigen::Index>(4 * result.points);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(rows, parameters);
  Eigen::Index row = 0;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const std::vector<cv::Point3f>& object = object_of(views[i], pattern_points);
    const auto points = static_cast<Eigen::Index>(object.size());
    const Eigen::Index pose_col = stereo_col + 6 + 6 * static_cast<Eigen::Index>(i);
    const ViewPose& pose = s.poses[i];
    const ViewProjection left = project_view(object, views[i].left_points, pose.rvec, pose.tvec,
                                             s.K[0], s.dist[0], s.model);
    const RightPose rp = compose_right(pose, s.om, s.T);
    const ViewProjection right =
        project_view(object, views[i].right_points, rp.rvec, rp.tvec, s.K[1], s.dist[1], s.model);
    for (Eigen::Index k = 0; k < n_free; ++k) {
      J.block(row, k, 2 * points, 1) = left.d_intrinsics.col(free[static_cast<std::size_t>(k)]);
      J.block(row + 2 * points, n_free + k, 2 * points, 1) =
          right.d_intrinsics.col(free[static_cast<std::size_t>(k)]);
    }
    J.block(row, pose_col, 2 * points, 6) = left.d_pose;
    J.block(row + 2 * points, pose_col, 2 * points, 6) = right.d_pose * rp.d_left_pose;
    J.block(row + 2 * points, stereo_col, 2 * points, 6) = right.d_pose * rp.d_stereo;
    result.sum_squares[0] += left.residual.squaredNorm();
    result.sum_squares[1] += right.residual.squaredNorm();
    row += 4 * points;
  }
  const double sigma2 =
      (result.sum_squares[0] + result.sum_squares[1]) / static_cast<double>(rows - parameters);
  const Eigen::MatrixXd JtJ = J.transpose() * J;
  const Eigen::MatrixXd covariance =
      sigma2 * JtJ.ldlt().solve(Eigen::MatrixXd::Identity(parameters, parameters));
  const Eigen::VectorXd sd = covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  for (int c = 0; c < 2; ++c) {
    std::vector<double> full(static_cast<std::size_t>(intrinsic_parameter_count(s.model)), 0.0);
    for (Eigen::Index k = 0; k < n_free; ++k)
      full[static_cast<std::size_t>(free[static_cast<std::size_t>(k)])] = sd(c * n_free + k);
    result.intrinsics[c] = intrinsics_std_dev(full, s.model);
  }
  result.rotation_std = sd.segment(stereo_col, 3);
  result.translation_std = sd.segment(stereo_col + 3, 3);
  Eigen::Vector3d t(s.T.at<double>(0), s.T.at<double>(1), s.T.at<double>(2));
  const Eigen::Vector3d g = t.normalized();
  result.baseline_std = std::sqrt(std::max(
      0.0, double(g.transpose() * covariance.block(stereo_col + 3, stereo_col + 3, 3, 3) * g)));
  return result;
}

}  // namespace

Status StereoCalibrationOptions::validate() const {
  if (Status s = calibration.validate(); !s) return s;
  if (!(rectify_alpha == -1.0 || (rectify_alpha >= 0.0 && rectify_alpha <= 1.0))) {
    return Error{"rectify_alpha must be -1 (OpenCV's default scaling) or in [0, 1]"};
  }
  return Status::Ok();
}

Result<StereoCalibration> calibrate_stereo(const CalibrationPattern& pattern,
                                           const std::vector<StereoPatternView>& views,
                                           cv::Size image_size,
                                           const StereoCalibrationOptions& options) {
  if (Status s = options.validate(); !s) return Error{"calibration options: " + s.error().message};
  {
    std::vector<PatternView> left, right;
    for (const StereoPatternView& v : views) {
      left.push_back({v.left_name, v.left_points, v.object_points});
      right.push_back({v.right_name, v.right_points, v.object_points});
    }
    if (Status s = check_views(left, pattern, image_size); !s) return s.error();
    if (Status s = check_views(right, pattern, image_size); !s) return s.error();
  }
  const int min_views = options.calibration.min_views;
  if (static_cast<int>(views.size()) < min_views) {
    return Error{too_few_views_message(views.size(), min_views, "stereo pairs")};
  }

  const std::vector<cv::Point3f> object = pattern_object_points(pattern);
  std::vector<StereoPatternView> active = views;
  std::vector<RejectedView> rejected;
  CalibrationOptions mono_options = options.calibration;
  mono_options.outlier_factor = 0.0;  // outliers are judged on the stereo solution

  while (true) {
    // Step 1: each camera alone.
    std::vector<PatternView> left_views, right_views;
    for (const StereoPatternView& v : active) {
      left_views.push_back({v.left_name, v.left_points, v.object_points});
      right_views.push_back({v.right_name, v.right_points, v.object_points});
    }
    auto mono_left = calibrate_mono(pattern, left_views, image_size, mono_options);
    if (!mono_left) return Error{"left camera: " + mono_left.error().message};
    auto mono_right = calibrate_mono(pattern, right_views, image_size, mono_options);
    if (!mono_right) return Error{"right camera: " + mono_right.error().message};

    // Step 2: joint refinement.
    const DistortionModel model = options.calibration.model;
    const bool fisheye = model == DistortionModel::equidistant;
    JointSolution s;
    s.model = model;
    s.K[0] = camera_matrix(mono_left->camera);
    s.K[1] = camera_matrix(mono_right->camera);
    s.dist[0] = distortion_vector(mono_left->camera);
    s.dist[1] = distortion_vector(mono_right->camera);
    std::vector<std::vector<cv::Point3f>> object_points;
    std::vector<std::vector<cv::Point2f>> left_points, right_points;
    for (const StereoPatternView& v : active) {
      object_points.push_back(object_of(v, object));
      left_points.push_back(v.left_points);
      right_points.push_back(v.right_points);
    }
    cv::Mat R, T, E, F, per_view;
    const cv::TermCriteria criteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS,
                                    options.calibration.max_iterations, 1e-10);
    double rms = 0.0;
    try {
      if (fisheye) {
        const int flags = options.refine_intrinsics
                              ? cv::fisheye::CALIB_USE_INTRINSIC_GUESS | cv::fisheye::CALIB_FIX_SKEW
                              : cv::fisheye::CALIB_FIX_INTRINSIC;
        cv::fisheye::stereoCalibrate(object_points, left_points, right_points, s.K[0], s.dist[0],
                                     s.K[1], s.dist[1], image_size, R, T, flags, criteria);
        for (cv::Mat& d : s.dist) d = d.reshape(1, 1);
      } else {
        // The model's flag also with fixed intrinsics: it tells OpenCV to use all 8 terms.
        const int model_flag =
            model == DistortionModel::rational_polynomial ? cv::CALIB_RATIONAL_MODEL : 0;
        const int flags = options.refine_intrinsics ? cv::CALIB_USE_INTRINSIC_GUESS |
                                                          calibration_flags(options.calibration)
                                                    : cv::CALIB_FIX_INTRINSIC | model_flag;
        rms =
            cv::stereoCalibrate(object_points, left_points, right_points, s.K[0], s.dist[0], s.K[1],
                                s.dist[1], image_size, R, T, E, F, per_view, flags, criteria);
        // CALIB_RATIONAL_MODEL returns (and needs) 8 coefficients, plumb_bob 5.
        for (cv::Mat& d : s.dist) {
          d = d.reshape(1, 1)
                  .colRange(0, static_cast<int>(distortion_coefficient_count(model)))
                  .clone();
        }
      }
    } catch (const cv::Exception& e) {
      return Error{"stereo calibration failed (" + e.msg +
                   "); use pairs tilted in different directions"};
    }
    if (!std::isfinite(rms) || !cv::checkRange(s.K[0]) || !cv::checkRange(s.K[1]) ||
        !cv::checkRange(s.dist[0]) || !cv::checkRange(s.dist[1]) || !cv::checkRange(R) ||
        !cv::checkRange(T)) {
      return Error{"stereo calibration diverged; use pairs tilted in different directions"};
    }
    R.convertTo(R, CV_64F);
    T = T.reshape(1, 3);
    T.convertTo(T, CV_64F);
    cv::Rodrigues(R, s.om);
    s.T = T.clone();
    if (fisheye) {
      // cv::fisheye::stereoCalibrate returns neither the per-view errors nor E and F: the
      // errors come from the left poses that fit both images (as for the covariance below),
      // E = [T]x R and F = K_R^-T E K_L^-1 as cv::stereoCalibrate forms them.
      solve_left_poses(object, active, s);
      per_view.create(static_cast<int>(active.size()), 2, CV_64F);
      double sum_squares = 0.0, total_points = 0.0;
      for (std::size_t k = 0; k < active.size(); ++k) {
        const ViewPose& pose = s.poses[k];
        const std::vector<cv::Point3f>& view_object = object_points[k];
        const ViewProjection left = project_view(view_object, active[k].left_points, pose.rvec,
                                                 pose.tvec, s.K[0], s.dist[0], model);
        const RightPose rp = compose_right(pose, s.om, s.T);
        const ViewProjection right = project_view(view_object, active[k].right_points, rp.rvec,
                                                  rp.tvec, s.K[1], s.dist[1], model);
        const double n = static_cast<double>(view_object.size());
        total_points += n;
        per_view.at<double>(static_cast<int>(k), 0) = std::sqrt(left.residual.squaredNorm() / n);
        per_view.at<double>(static_cast<int>(k), 1) = std::sqrt(right.residual.squaredNorm() / n);
        sum_squares += left.residual.squaredNorm() + right.residual.squaredNorm();
      }
      rms = std::sqrt(sum_squares / (2.0 * total_points));
      const cv::Matx33d Tx(0.0, -T.at<double>(2), T.at<double>(1), T.at<double>(2), 0.0,
                           -T.at<double>(0), -T.at<double>(1), T.at<double>(0), 0.0);
      E = cv::Mat(Tx * cv::Matx33d(R));
      F = cv::Mat(cv::Matx33d(s.K[1]).inv().t() * cv::Matx33d(E) * cv::Matx33d(s.K[0]).inv());
    }

    // Step 3: outliers, in either image.
    double worst_ratio = 0.0, worst_error = 0.0, worst_median = 0.0;
    std::size_t worst = 0;
    const char* worst_side = "left";
    for (int c = 0; c < 2; ++c) {
      std::vector<double> errors;
      for (int k = 0; k < per_view.rows; ++k) errors.push_back(per_view.at<double>(k, c));
      const double median = median_of(errors);
      for (std::size_t k = 0; k < errors.size(); ++k) {
        const double ratio = median > 0.0 ? errors[k] / median : 0.0;
        if (ratio > worst_ratio && errors[k] > options.calibration.outlier_floor_px) {
          worst_ratio = ratio;
          worst_error = errors[k];
          worst_median = median;
          worst = k;
          worst_side = c == 0 ? "left" : "right";
        }
      }
    }
    if (options.calibration.outlier_factor > 0.0 &&
        worst_ratio > options.calibration.outlier_factor &&
        static_cast<int>(active.size()) > min_views) {
      char factor[16];
      std::snprintf(factor, sizeof factor, "%g", options.calibration.outlier_factor);
      rejected.push_back({.name = active[worst].left_name,
                          .right_name = active[worst].right_name,
                          .reason = std::string("outlier: ") + worst_side + " reprojection RMS " +
                                    core::format_fixed(worst_error, 3, "px") + " > " + factor +
                                    " x median " + core::format_fixed(worst_median, 3, "px")});
      active.erase(active.begin() + static_cast<std::ptrdiff_t>(worst));
      continue;
    }

    // Step 4: rectification, uncertainty, output.
    StereoCalibration result;
    result.rms_px = rms;
    result.mono_left_rms_px = mono_left->rms_px;
    result.mono_right_rms_px = mono_right->rms_px;
    result.R = cv::Matx33d(R);
    result.T = cv::Vec3d(T.at<double>(0), T.at<double>(1), T.at<double>(2));
    result.E = cv::Matx33d(E);
    result.F = cv::Matx33d(F);
    StereoRectification& rect = result.rectification;
    cv::Mat R1, R2, P1, P2, Q;
    if (fisheye) {
      // Bouguet's rectification for the fisheye model; alpha is its `balance` (OpenCV's
      // default scaling, -1, is balance 0). It computes no valid-pixel rectangles: the whole
      // image is reported.
      cv::fisheye::stereoRectify(s.K[0], s.dist[0], s.K[1], s.dist[1], image_size, R, T, R1, R2, P1,
                                 P2, Q, cv::fisheye::CALIB_ZERO_DISPARITY, image_size,
                                 std::max(0.0, options.rectify_alpha));
      rect.left_roi = rect.right_roi = cv::Rect(0, 0, image_size.width, image_size.height);
    } else {
      cv::stereoRectify(s.K[0], s.dist[0], s.K[1], s.dist[1], image_size, R, T, R1, R2, P1, P2, Q,
                        cv::CALIB_ZERO_DISPARITY, options.rectify_alpha, image_size, &rect.left_roi,
                        &rect.right_roi);
    }
    rect.R1 = cv::Matx33d(R1);
    rect.R2 = cv::Matx33d(R2);
    rect.P1 = cv::Matx34d(P1);
    rect.P2 = cv::Matx34d(P2);
    rect.Q = cv::Matx44d(Q);

    if (!fisheye) solve_left_poses(object, active, s);
    const Covariance cov = joint_covariance(object, active, s, free_intrinsics(options));
    result.left_std_dev = options.refine_intrinsics ? cov.intrinsics[0] : mono_left->std_dev;
    result.right_std_dev = options.refine_intrinsics ? cov.intrinsics[1] : mono_right->std_dev;
    result.rotation_std = cov.rotation_std;
    result.translation_std = cov.translation_std;
    result.baseline_std = cov.baseline_std;
    result.left_rms_px = std::sqrt(cov.sum_squares[0] / static_cast<double>(cov.points));
    result.right_rms_px = std::sqrt(cov.sum_squares[1] / static_cast<double>(cov.points));

    result.cameras.left = camera_from(s.K[0], s.dist[0], image_size, model);
    result.cameras.right = camera_from(s.K[1], s.dist[1], image_size, model);
    result.cameras.right.T_cam_base = pose_from_rvec_tvec(s.om, s.T);
    for (std::size_t k = 0; k < active.size(); ++k) {
      StereoCalibratedView view;
      view.left_name = active[k].left_name;
      view.right_name = active[k].right_name;
      view.left_rms_px = per_view.at<double>(static_cast<int>(k), 0);
      view.right_rms_px = per_view.at<double>(static_cast<int>(k), 1);
      view.T_left_target = pose_from_rvec_tvec(s.poses[k].rvec, s.poses[k].tvec);
      result.views.push_back(std::move(view));
    }
    result.rejected = std::move(rejected);
    return result;
  }
}

}  // namespace telear::vision
