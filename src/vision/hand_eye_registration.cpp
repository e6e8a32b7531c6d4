#include "telear/vision/hand_eye_registration.hpp"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "telear/core/angles.hpp"
#include "telear/core/kinematics.hpp"
#include "telear/core/number_format.hpp"
#include "telear/vision/opencv_pose.hpp"

#include "vision_text.hpp"

namespace telear::vision {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;

constexpr int kMaxRounds = 3;
// Two rotation axes closer than this are one axis for the degeneracy check (deg).
constexpr double kParallelAxesDeg = 10.0;

// exp(delta) * T: rotate by the rotation vector delta[0..2] about the origin of the frame T
// maps into, then translate by delta[3..5]. The solver's parameters are such perturbations of
// a reference pose, so at delta = 0 they are small-angle rotations and translations in the
// camera (or flange) frame and their covariance reads directly in radians and metres.
Eigen::Isometry3d perturbed(const Vector6& delta, const Eigen::Isometry3d& T) {
  Eigen::Isometry3d E = Eigen::Isometry3d::Identity();
  const double angle = delta.head<3>().norm();
  if (angle > 0.0) E.linear() = Eigen::AngleAxisd(angle, delta.head<3>() / angle).matrix();
  E.translation() = delta.tail<3>();
  return E * T;
}

// The camera model of camera_model.hpp (pinhole, skew, any of the three lens models), for
// automatic derivatives. False for points at or behind the camera's z = 0 plane.
template <typename T>
bool project(const CameraModel& c, const T* p_cam, T* uv) {
  if (!(p_cam[2] > T(1e-9))) return false;
  const T x = p_cam[0] / p_cam[2];
  const T y = p_cam[1] / p_cam[2];
  T xd, yd;
  distort_normalized(c.kc, x, y, xd, yd);
  uv[0] = T(c.fx) * (xd + T(c.alpha_c) * yd) + T(c.cx);
  uv[1] = T(c.fy) * yd + T(c.cy);
  return true;
}

// Reference poses the parameters perturb; shared by every residual of one problem.
struct References {
  Eigen::Isometry3d T_left_base = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_flange_target = Eigen::Isometry3d::Identity();
};

// One detected point of one eye at one view.
struct PointResidual {
  const CameraModel* camera = nullptr;
  const References* references = nullptr;
  Eigen::Isometry3d T_base_flange;
  Eigen::Isometry3d T_eye_left;  // identity for the left eye, T_right_left for the right
  Eigen::Vector3d p_target;
  Eigen::Vector2d pixel;

  template <typename T>
  bool operator()(const T* base, const T* target, T* residual) const {
    // The point on the flange: exp(target) * T_flange_target_ref * p.
    const Eigen::Vector3d p_ref = references->T_flange_target * p_target;
    const T p0[3] = {T(p_ref.x()), T(p_ref.y()), T(p_ref.z())};
    T p_flange[3];
    ceres::AngleAxisRotatePoint(target, p0, p_flange);
    for (int k = 0; k < 3; ++k) p_flange[k] += target[3 + k];
    // In the left camera: exp(base) * (T_left_base_ref * T_base_flange) * p_flange.
    const Eigen::Isometry3d M = references->T_left_base * T_base_flange;
    T p_left_ref[3];
    for (int r = 0; r < 3; ++r) {
      p_left_ref[r] = T(M(r, 3));
      for (int k = 0; k < 3; ++k) p_left_ref[r] += T(M(r, k)) * p_flange[k];
    }
    T p_left[3];
    ceres::AngleAxisRotatePoint(base, p_left_ref, p_left);
    for (int k = 0; k < 3; ++k) p_left[k] += base[3 + k];
    T p_cam[3];
    for (int r = 0; r < 3; ++r) {
      p_cam[r] = T(T_eye_left(r, 3));
      for (int k = 0; k < 3; ++k) p_cam[r] += T(T_eye_left(r, k)) * p_left[k];
    }
    T uv[2];
    if (!project(*camera, p_cam, uv)) return false;
    residual[0] = uv[0] - T(pixel.x());
    residual[1] = uv[1] - T(pixel.y());
    return true;
  }

  // The pixel error at the reference poses (parameters zero); infinity behind the camera.
  double error_px() const {
    const double zero[6] = {0, 0, 0, 0, 0, 0};
    double r[2];
    if (!(*this)(zero, zero, r)) return std::numeric_limits<double>::infinity();
    return std::hypot(r[0], r[1]);
  }
};

struct ViewData {
  const HandEyeView* view = nullptr;
  Eigen::Isometry3d T_base_flange;
  bool dropped = false;
};

bool finite(const Eigen::Vector2d& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y());
}

Status check_eye(const std::vector<TargetPixel>& pixels, std::size_t points,
                 const std::string& where) {
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const TargetPixel& p = pixels[i];
    if (p.point < 0 || static_cast<std::size_t>(p.point) >= points) {
      return Error{where + "[" + std::to_string(i) + "]: point " + std::to_string(p.point) +
                   " is not one of the target's " + std::to_string(points) + " points"};
    }
    if (!finite(p.pixel)) {
      return Error{where + "[" + std::to_string(i) + "]: pixel is not finite"};
    }
  }
  return {};
}

// Whether the target points (those indexed) lie on one plane.
bool planar(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& p : points) scatter += (p - mean) * (p - mean).transpose();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(scatter);
  const Eigen::Vector3d s = svd.singularValues();
  return s[2] <= 1e-12 * std::max(s[0], 1e-300);
}

cv::Mat to_cv(const Eigen::Matrix3d& m) {
  cv::Mat out;
  cv::eigen2cv(m, out);
  return out;
}
cv::Mat to_cv(const Eigen::Vector3d& v) {
  cv::Mat out;
  cv::eigen2cv(v, out);
  return out;
}
Eigen::Isometry3d from_cv(const cv::Mat& R, const cv::Mat& t) {
  Eigen::Matrix3d r;
  Eigen::Vector3d v;
  cv::cv2eigen(R, r);
  cv::cv2eigen(t, v);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = r;
  T.translation() = v;
  return T;
}

EyeResiduals eye_residuals(const std::vector<PointResidual>& residuals) {
  EyeResiduals out;
  double sum = 0.0;
  for (const PointResidual& r : residuals) {
    const double e = r.error_px();
    sum += e * e;
    out.max_px = std::max(out.max_px, e);
    ++out.observations;
  }
  if (out.observations > 0) out.rms_px = std::sqrt(sum / out.observations);
  return out;
}

// Builds one eye's residuals for the given views at the given references.
std::vector<PointResidual> eye_points(const CameraModel& camera, const References& references,
                                      const Eigen::Isometry3d& T_eye_left,
                                      const HandEyeObservations& observations,
                                      const std::vector<ViewData>& views, bool right,
                                      std::vector<int>* view_of_point = nullptr) {
  std::vector<PointResidual> out;
  for (std::size_t v = 0; v < views.size(); ++v) {
    if (views[v].dropped) continue;
    const auto& pixels = right ? views[v].view->right : views[v].view->left;
    for (const TargetPixel& p : pixels) {
      out.push_back({&camera, &references, views[v].T_base_flange, T_eye_left,
                     observations.target_points[static_cast<std::size_t>(p.point)], p.pixel});
      if (view_of_point) view_of_point->push_back(static_cast<int>(v));
    }
  }
  return out;
}

// Step 1 for one eye: PnP per view, then Shah's closed form.
HandEyeBaseline shah_li(const CameraModel& camera, const HandEyeObservations& observations,
                        const std::vector<ViewData>& views, bool right) {
  HandEyeBaseline out;
  std::vector<cv::Mat> R_world2cam, t_world2cam, R_base2gripper, t_base2gripper;
  for (const ViewData& v : views) {
    const auto& pixels = right ? v.view->right : v.view->left;
    const auto T_cam_target = target_pose_in_camera(camera, observations.target_points, pixels);
    if (!T_cam_target) continue;
    const Eigen::Isometry3d T_flange_base = v.T_base_flange.inverse();
    const Eigen::Isometry3d T_target_cam = T_cam_target->inverse();
    R_world2cam.push_back(to_cv(Eigen::Matrix3d(T_flange_base.linear())));
    t_world2cam.push_back(to_cv(Eigen::Vector3d(T_flange_base.translation())));
    R_base2gripper.push_back(to_cv(Eigen::Matrix3d(T_target_cam.linear())));
    t_base2gripper.push_back(to_cv(Eigen::Vector3d(T_target_cam.translation())));
  }
  out.views = static_cast<int>(R_world2cam.size());
  if (out.views < 3) return out;
  cv::Mat R_base2world, t_base2world, R_gripper2cam, t_gripper2cam;
  try {
    cv::calibrateRobotWorldHandEye(R_world2cam, t_world2cam, R_base2gripper, t_base2gripper,
                                   R_base2world, t_base2world, R_gripper2cam, t_gripper2cam,
                                   cv::CALIB_ROBOT_WORLD_HAND_EYE_SHAH);
  } catch (const cv::Exception&) {
    return out;
  }
  const Eigen::Isometry3d T_base_cam = from_cv(R_base2world, t_base2world);
  out.T_cam_base = T_base_cam.inverse();
  out.T_flange_target = from_cv(R_gripper2cam, t_gripper2cam);
  if (!out.T_cam_base.matrix().allFinite() || !out.T_flange_target.matrix().allFinite()) {
    return out;
  }
  out.solved = true;
  References refs{out.T_cam_base, out.T_flange_target};
  out.residuals = eye_residuals(
      eye_points(camera, refs, Eigen::Isometry3d::Identity(), observations, views, right));
  return out;
}

// AX = ZB needs rotations about two non-parallel axes.
Status check_rotations(const std::vector<ViewData>& views, double min_deg) {
  std::vector<Eigen::Vector3d> axes;
  for (std::size_t i = 0; i < views.size(); ++i) {
    for (std::size_t j = i + 1; j < views.size(); ++j) {
      // The axis of R_j R_i^T, in the base frame: constant when every pose turns the flange
      // about one fixed axis, whether that axis is fixed in the base (joint 1 alone) or in the
      // flange (the last joint alone).
      const Eigen::Matrix3d R_i = views[i].T_base_flange.linear();
      const Eigen::Matrix3d R_j = views[j].T_base_flange.linear();
      const Eigen::AngleAxisd aa(Eigen::Matrix3d(R_j * R_i.transpose()));
      if (std::abs(aa.angle()) < core::radians_from_degrees(min_deg)) continue;
      axes.push_back(aa.axis());
    }
  }
  if (axes.empty()) {
    return Error{"the flange turns by less than " + fixed(min_deg, 1) +
                 " deg between every two poses: the target's place on the flange cannot be "
                 "told from the base's; capture poses that tilt and turn the wrist"};
  }
  const double sin_parallel = std::sin(core::radians_from_degrees(kParallelAxesDeg));
  for (const Eigen::Vector3d& a : axes) {
    if (a.cross(axes.front()).norm() > sin_parallel) return {};
  }
  const Eigen::Vector3d& a = axes.front();
  return Error{"every rotation between the poses turns the flange about one axis (within " +
               fixed(kParallelAxesDeg, 0) + " deg of [" + fixed(a.x(), 2) + ", " + fixed(a.y(), 2) +
               ", " + fixed(a.z(), 2) +
               "] in the base frame): the registration is degenerate along it; capture "
               "poses that also turn the wrist about another axis"};
}

// 1-sigma position (of `origin`, the frame's origin moved by the perturbation) and rotation.
PoseSigma sigma_of(const Eigen::Matrix<double, 6, 6>& covariance, const Eigen::Vector3d& origin) {
  // A perturbation (w, d) moves the origin by w x origin + d.
  Eigen::Matrix<double, 3, 6> J;
  J.leftCols<3>() << 0, origin.z(), -origin.y(), -origin.z(), 0, origin.x(), origin.y(),
      -origin.x(), 0;
  J.rightCols<3>().setIdentity();
  const Eigen::Matrix3d position = J * covariance * J.transpose();
  PoseSigma s;
  s.position_mm = 1000.0 * std::sqrt(std::max(0.0, position.trace()));
  s.rotation_deg = core::degrees_from_radians(
      std::sqrt(std::max(0.0, covariance.topLeftCorner<3, 3>().trace())));
  return s;
}

}  // namespace

std::optional<Eigen::Isometry3d> target_pose_in_camera(const CameraModel& camera,
                                                       const std::vector<Eigen::Vector3d>& target,
                                                       const std::vector<TargetPixel>& pixels) {
  if (pixels.size() < 4) return std::nullopt;
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  std::vector<Eigen::Vector3d> used;
  const double max_radius = camera.max_monotonic_radius();
  for (const TargetPixel& p : pixels) {
    const auto x = camera.undistort_within(camera.normalized_from_pixel(p.pixel), max_radius);
    if (!x) continue;
    const Eigen::Vector3d& P = target[static_cast<std::size_t>(p.point)];
    object.emplace_back(P.x(), P.y(), P.z());
    image.emplace_back(x->x(), x->y());
    used.push_back(P);
  }
  if (object.size() < 4) return std::nullopt;
  const cv::Mat K = cv::Mat::eye(3, 3, CV_64F);
  cv::Mat rvec, tvec;
  const int method = planar(used) ? cv::SOLVEPNP_IPPE : cv::SOLVEPNP_SQPNP;
  try {
    if (!cv::solvePnP(object, image, K, cv::noArray(), rvec, tvec, false, method)) {
      return std::nullopt;
    }
  } catch (const cv::Exception&) {
    return std::nullopt;
  }
  return pose_from_rvec_tvec(rvec, tvec);
}

HandEyeObservations hand_eye_observations(const RegistrationObservations& observations) {
  HandEyeObservations out;
  out.target_points = observations.point_in_flange;
  for (std::size_t c = 0; c < observations.configurations.size(); ++c) {
    const ObservedConfiguration& configuration = observations.configurations[c];
    HandEyeView view;
    view.name = "configuration " + std::to_string(c);
    view.q = configuration.q;
    for (std::size_t i = 0; i < configuration.left_pixels.size(); ++i) {
      view.left.push_back({static_cast<int>(i), configuration.left_pixels[i]});
    }
    for (std::size_t i = 0; i < configuration.right_pixels.size(); ++i) {
      view.right.push_back({static_cast<int>(i), configuration.right_pixels[i]});
    }
    out.views.push_back(std::move(view));
  }
  return out;
}

Status HandEyeOptions::validate() const {
  auto bad = [](const std::string& field, double value, const std::string& range) {
    return Error{"hand-eye option " + field + " = " + core::format_number(value) + " must be " +
                 range};
  };
  if (!(loss_scale_px > 0.0 && loss_scale_px <= 100.0))
    return bad("loss_scale_px", loss_scale_px, "in (0, 100] px");
  if (!(outlier_factor >= 1.0 && outlier_factor <= 1000.0))
    return bad("outlier_factor", outlier_factor, "in [1, 1000]");
  if (!(outlier_min_px > 0.0 && outlier_min_px <= 1000.0))
    return bad("outlier_min_px", outlier_min_px, "in (0, 1000] px");
  if (min_views < 3 || min_views > 10000) return bad("min_views", min_views, "in [3, 10000]");
  if (max_iterations < 1 || max_iterations > 100000)
    return bad("max_iterations", max_iterations, "in [1, 100000]");
  if (!(max_sigma_mm > 0.0)) return bad("max_sigma_mm", max_sigma_mm, "positive");
  if (!(max_sigma_deg > 0.0)) return bad("max_sigma_deg", max_sigma_deg, "positive");
  if (!(min_rotation_deg > 0.0 && min_rotation_deg < 90.0))
    return bad("min_rotation_deg", min_rotation_deg, "in (0, 90) deg");
  return {};
}

Result<HandEyeResult> register_hand_eye(const core::RobotModel& model, const CameraModel& left,
                                        const CameraModel& right,
                                        const Eigen::Isometry3d& T_right_left,
                                        const HandEyeObservations& observations,
                                        const HandEyeOptions& options) {
  if (Status s = options.validate(); !s) return s.error();
  if (Status s = validate_camera(left); !s) return Error{"left camera: " + s.error().message};
  if (Status s = validate_camera(right); !s) return Error{"right camera: " + s.error().message};
  if (!T_right_left.matrix().allFinite()) return Error{"T_right_left is not finite"};
  if (observations.target_points.empty()) return Error{"the target has no points"};
  for (std::size_t i = 0; i < observations.target_points.size(); ++i) {
    if (!observations.target_points[i].allFinite()) {
      return Error{"target point " + std::to_string(i) + " is not finite"};
    }
  }

  HandEyeResult result;
  std::vector<ViewData> views;
  core::KinematicsData data(model);
  for (const HandEyeView& view : observations.views) {
    if (view.q.size() != model.dof()) {
      return Error{view.name + ": " + std::to_string(view.q.size()) + " joint values, but robot '" +
                   model.name() + "' has " + std::to_string(model.dof()) + " joints"};
    }
    if (!view.q.allFinite()) return Error{view.name + ": q is not finite"};
    const std::size_t n = observations.target_points.size();
    if (Status s = check_eye(view.left, n, view.name + ": left"); !s) return s.error();
    if (Status s = check_eye(view.right, n, view.name + ": right"); !s) return s.error();
    if (view.left.empty() && view.right.empty()) {
      result.notes.push_back(view.name + " set aside: the target was seen by neither eye");
      continue;
    }
    core::forward_kinematics(model, data, view.q);
    views.push_back({&view, data.T_base_link.back(), false});
  }
  if (static_cast<int>(views.size()) < options.min_views) {
    return Error{std::to_string(views.size()) +
                 " usable poses (the target seen by at least one eye), at least " +
                 std::to_string(options.min_views) +
                 " are needed: capture more poses where both cameras see the target"};
  }
  if (Status s = check_rotations(views, options.min_rotation_deg); !s) return s.error();

  // Step 1: the baseline of each eye, and the start.
  result.baseline_left = shah_li(left, observations, views, false);
  result.baseline_right = shah_li(right, observations, views, true);
  References references;
  if (result.baseline_left.solved) {
    references = {result.baseline_left.T_cam_base, result.baseline_left.T_flange_target};
  } else if (result.baseline_right.solved) {
    references = {T_right_left.inverse() * result.baseline_right.T_cam_base,
                  result.baseline_right.T_flange_target};
  } else {
    return Error{"no eye saw the target with at least 4 points at 3 or more poses (left " +
                 std::to_string(result.baseline_left.views) + ", right " +
                 std::to_string(result.baseline_right.views) +
                 " such poses): bring the target into both cameras' view"};
  }
  const std::pair<const char*, const HandEyeBaseline*> baselines[] = {
      {"left", &result.baseline_left}, {"right", &result.baseline_right}};
  for (const auto& [eye, b] : baselines) {
    if (!b->solved) {
      result.notes.push_back(std::string(eye) + " eye: no closed-form baseline (" +
                             std::to_string(b->views) +
                             " poses with the target's pose, at least 3 needed)");
    }
  }

  // Steps 2 and 3: bundle adjustment, dropping outlier views between rounds.
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  std::vector<ViewFit> dropped_fits;  // kept for the report across rounds
  for (int round = 0; round < kMaxRounds; ++round) {
    std::vector<int> view_of_point;
    std::vector<PointResidual> points =
        eye_points(left, references, identity, observations, views, false, &view_of_point);
    std::vector<PointResidual> right_points =
        eye_points(right, references, T_right_left, observations, views, true, &view_of_point);
    const std::size_t left_count = points.size();
    points.insert(points.end(), right_points.begin(), right_points.end());
    if (points.size() < 7) {
      return Error{std::to_string(points.size()) +
                   " detected points in all: too few to estimate 12 parameters"};
    }

    double base[6] = {0, 0, 0, 0, 0, 0};
    double target[6] = {0, 0, 0, 0, 0, 0};
    ceres::Problem::Options problem_options;
    problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
    problem_options.loss_function_ownership = ceres::TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    for (const PointResidual& p : points) {
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<PointResidual, 2, 6, 6>(new PointResidual(p)),
          new ceres::HuberLoss(options.loss_scale_px), base, target);
    }
    ceres::Solver::Options solver_options;
    solver_options.linear_solver_type = ceres::DENSE_QR;
    solver_options.max_num_iterations = options.max_iterations;
    solver_options.function_tolerance = 1e-14;
    solver_options.parameter_tolerance = 1e-14;
    solver_options.gradient_tolerance = 1e-16;
    solver_options.num_threads = 1;
    solver_options.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options, &problem, &summary);
    result.iterations += static_cast<int>(summary.iterations.size());
    if (!summary.IsSolutionUsable()) {
      return Error{"the bundle adjustment failed: " + summary.message};
    }
    references.T_left_base = perturbed(Eigen::Map<const Vector6>(base), references.T_left_base);
    references.T_flange_target =
        perturbed(Eigen::Map<const Vector6>(target), references.T_flange_target);

    // Per-view fit at the new references.
    std::vector<double> sum(views.size(), 0.0);
    std::vector<int> count(views.size(), 0);
    std::vector<int> left_n(views.size(), 0), right_n(views.size(), 0);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto v = static_cast<std::size_t>(view_of_point[i]);
      const double e = points[i].error_px();
      sum[v] += e * e;
      ++count[v];
      (i < left_count ? left_n : right_n)[v]++;
    }
    result.views.clear();
    std::vector<double> rms_of_used;
    for (std::size_t v = 0; v < views.size(); ++v) {
      if (views[v].dropped) continue;
      ViewFit fit;
      fit.name = views[v].view->name;
      fit.left_points = left_n[v];
      fit.right_points = right_n[v];
      fit.rms_px = count[v] > 0 ? std::sqrt(sum[v] / count[v]) : 0.0;
      result.views.push_back(fit);
      rms_of_used.push_back(fit.rms_px);
    }
    std::vector<double> sorted = rms_of_used;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2),
                     sorted.end());
    const double median = sorted[sorted.size() / 2];
    const double limit = std::max(options.outlier_min_px, options.outlier_factor * median);
    bool dropped_any = false;
    std::size_t fit_index = 0;
    int remaining = 0;
    for (std::size_t v = 0; v < views.size(); ++v) {
      if (views[v].dropped) continue;
      ViewFit& fit = result.views[fit_index++];
      if (fit.rms_px > limit && round + 1 < kMaxRounds) {
        views[v].dropped = true;
        fit.dropped = true;
        dropped_any = true;
        dropped_fits.push_back(fit);
        result.notes.push_back(fit.name + " dropped as an outlier: RMS " + fixed(fit.rms_px, 2) +
                               " px against the median pose's " + fixed(median, 2) +
                               " px (was the target partly hidden or seen edge-on there, did "
                               "the arm move during the capture, or the target slip on the "
                               "flange?)");
      } else {
        ++remaining;
      }
    }
    result.views_used = remaining;
    if (!dropped_any) {
      // Final residuals and the uncertainty, at the references (parameters zero).
      std::vector<PointResidual> final_left(points.begin(),
                                            points.begin() + static_cast<long>(left_count));
      std::vector<PointResidual> final_right(points.begin() + static_cast<long>(left_count),
                                             points.end());
      result.left = eye_residuals(final_left);
      result.right = eye_residuals(final_right);
      std::fill(base, base + 6, 0.0);
      std::fill(target, target + 6, 0.0);
      ceres::Covariance::Options covariance_options;
      covariance_options.algorithm_type = ceres::DENSE_SVD;
      covariance_options.null_space_rank = 0;
      covariance_options.num_threads = 1;
      ceres::Covariance covariance(covariance_options);
      const std::vector<std::pair<const double*, const double*>> blocks = {
          {base, base}, {target, target}, {base, target}};
      if (!covariance.Compute(blocks, &problem)) {
        return Error{
            "the registration is poorly conditioned (the problem is rank deficient): "
            "capture poses that spread the target over the images and turn the wrist "
            "about different axes"};
      }
      Eigen::Matrix<double, 6, 6, Eigen::RowMajor> base_cov, target_cov;
      covariance.GetCovarianceBlock(base, base, base_cov.data());
      covariance.GetCovarianceBlock(target, target, target_cov.data());
      double squares = 0.0;
      for (const PointResidual& p : points) squares += p.error_px() * p.error_px();
      const double dof = 2.0 * static_cast<double>(points.size()) - 12.0;
      const double variance = dof > 0.0 ? squares / dof : squares;
      result.base_sigma = sigma_of(variance * base_cov, references.T_left_base.translation());
      result.target_sigma =
          sigma_of(variance * target_cov, references.T_flange_target.translation());
      break;
    }
    if (remaining < options.min_views) {
      return Error{"only " + std::to_string(remaining) + " poses left after dropping outliers (" +
                   std::to_string(options.min_views) +
                   " needed): check that the target is fixed to the flange and recapture"};
    }
  }

  result.views.insert(result.views.end(), dropped_fits.begin(), dropped_fits.end());
  result.T_left_base = references.T_left_base;
  result.T_right_base = T_right_left * references.T_left_base;
  result.T_flange_target = references.T_flange_target;
  if (result.base_sigma.position_mm > options.max_sigma_mm ||
      result.base_sigma.rotation_deg > options.max_sigma_deg) {
    return Error{"the registration is poorly conditioned: the base is known only to " +
                 fixed(result.base_sigma.position_mm, 2) + " mm and " +
                 fixed(result.base_sigma.rotation_deg, 3) + " deg (1 sigma; limits " +
                 fixed(options.max_sigma_mm, 2) + " mm, " + fixed(options.max_sigma_deg, 3) +
                 " deg): capture more poses, spread over the images and turning the wrist"};
  }
  return result;
}

}  // namespace telear::vision
