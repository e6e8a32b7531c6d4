#include "telear/vision/registration.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>

#include "telear/core/kinematics.hpp"
#include "telear/core/number_format.hpp"
#include "telear/vision/opencv_pose.hpp"

namespace telear::vision {
namespace {

// One observed point: where it is in the base frame and the pixel one eye saw.
struct Observation {
  Eigen::Vector3d p_base;
  Eigen::Vector2d pixel;
  int configuration = 0;
};

struct EyeObservations {
  std::vector<Observation> left;
  std::vector<Observation> right;
};

Eigen::Isometry3d exp_left(const Eigen::Matrix<double, 6, 1>& delta) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const double angle = delta.head<3>().norm();
  if (angle > 0.0) T.linear() = Eigen::AngleAxisd(angle, delta.head<3>() / angle).matrix();
  T.translation() = delta.tail<3>();
  return T;
}

// Pixel residuals of one eye, appended to `r`; false when a point is behind the camera.
bool append_residuals(const CameraModel& camera, const Eigen::Isometry3d& T_cam_base,
                      const std::vector<Observation>& observations, std::vector<double>& r) {
  CameraModel posed = camera;
  posed.T_cam_base = T_cam_base;
  for (const Observation& o : observations) {
    const std::optional<Eigen::Vector2d> uv = posed.project(o.p_base);
    if (!uv) return false;
    r.push_back(uv->x() - o.pixel.x());
    r.push_back(uv->y() - o.pixel.y());
  }
  return true;
}

EyeResiduals summarize(const CameraModel& camera, const Eigen::Isometry3d& T_cam_base,
                       const std::vector<Observation>& observations) {
  EyeResiduals result;
  CameraModel posed = camera;
  posed.T_cam_base = T_cam_base;
  double sum = 0.0;
  for (const Observation& o : observations) {
    const std::optional<Eigen::Vector2d> uv = posed.project(o.p_base);
    const double error = uv ? (*uv - o.pixel).norm() : std::numeric_limits<double>::infinity();
    sum += error * error;
    result.max_px = std::max(result.max_px, error);
    ++result.observations;
  }
  if (result.observations > 0) result.rms_px = std::sqrt(sum / result.observations);
  return result;
}

struct Problem {
  const CameraModel* left;
  const CameraModel* right;
  Eigen::Isometry3d T_right_left;
  const EyeObservations* observations;

  // Residual vector at T_left_base; empty when a point falls behind a camera.
  std::vector<double> residuals(const Eigen::Isometry3d& T_left_base) const {
    std::vector<double> r;
    r.reserve(2 * (observations->left.size() + observations->right.size()));
    if (!append_residuals(*left, T_left_base, observations->left, r)) return {};
    if (!append_residuals(*right, T_right_left * T_left_base, observations->right, r)) return {};
    return r;
  }
};

double cost(const std::vector<double>& r) {
  double sum = 0.0;
  for (double v : r) sum += v * v;
  return sum;
}

// Hand-written Levenberg-Marquardt on the 6 parameters of a left perturbation.
int refine(const Problem& problem, Eigen::Isometry3d& T_left_base, int max_iterations) {
  std::vector<double> r = problem.residuals(T_left_base);
  if (r.empty()) return 0;
  double current = cost(r);
  double lambda = 1e-3;
  const Eigen::Index m = static_cast<Eigen::Index>(r.size());
  int iteration = 0;
  for (; iteration < max_iterations; ++iteration) {
    Eigen::MatrixXd J(m, 6);
    bool ok = true;
    for (int k = 0; k < 6 && ok; ++k) {
      // Rotation steps of 1e-7 rad and translation steps of 1e-7 m: central differences
      // then carry ~1e-14 relative truncation error, far below the pixel noise.
      Eigen::Matrix<double, 6, 1> h = Eigen::Matrix<double, 6, 1>::Zero();
      h[k] = 1e-7;
      const std::vector<double> plus = problem.residuals(exp_left(h) * T_left_base);
      const std::vector<double> minus = problem.residuals(exp_left(-h) * T_left_base);
      if (plus.empty() || minus.empty()) {
        ok = false;
        break;
      }
      for (Eigen::Index i = 0; i < m; ++i) {
        J(i, k) = (plus[static_cast<std::size_t>(i)] - minus[static_cast<std::size_t>(i)]) / 2e-7;
      }
    }
    if (!ok) break;
    const Eigen::Map<const Eigen::VectorXd> rv(r.data(), m);
    const Eigen::Matrix<double, 6, 6> JtJ = J.transpose() * J;
    const Eigen::Matrix<double, 6, 1> Jtr = J.transpose() * rv;
    bool improved = false;
    for (int attempt = 0; attempt < 20; ++attempt) {
      Eigen::Matrix<double, 6, 6> A = JtJ;
      A.diagonal() += lambda * JtJ.diagonal().cwiseMax(1e-12);
      const Eigen::Matrix<double, 6, 1> step = A.ldlt().solve(-Jtr);
      const Eigen::Isometry3d candidate = exp_left(step) * T_left_base;
      const std::vector<double> rc = problem.residuals(candidate);
      if (!rc.empty() && cost(rc) < current) {
        T_left_base = candidate;
        r = rc;
        const double previous = current;
        current = cost(rc);
        lambda = std::max(lambda / 10.0, 1e-12);
        improved = true;
        if (step.norm() < 1e-10 || previous - current < 1e-14 * previous) {
          return iteration + 1;
        }
        break;
      }
      lambda *= 10.0;
    }
    if (!improved) break;
  }
  return iteration;
}

// T_cam_base by SQPnP on one eye's observations (undistorted to normalized coordinates).
std::optional<Eigen::Isometry3d> pnp(const CameraModel& camera,
                                     const std::vector<Observation>& observations) {
  if (observations.size() < 3) return std::nullopt;
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (const Observation& o : observations) {
    const std::optional<Eigen::Vector2d> x =
        camera.undistort(camera.normalized_from_pixel(o.pixel));
    if (!x) continue;
    object.emplace_back(o.p_base.x(), o.p_base.y(), o.p_base.z());
    image.emplace_back(x->x(), x->y());
  }
  if (object.size() < 3) return std::nullopt;
  cv::Mat rvec, tvec;
  try {
    if (!cv::solvePnP(object, image, cv::Mat::eye(3, 3, CV_64F), cv::Mat(), rvec, tvec, false,
                      cv::SOLVEPNP_SQPNP)) {
      return std::nullopt;
    }
  } catch (const cv::Exception&) {
    return std::nullopt;
  }
  const Eigen::Isometry3d T = pose_from_rvec_tvec(rvec, tvec);
  if (!T.matrix().allFinite()) return std::nullopt;
  return T;
}

Result<EyeObservations> collect(const core::RobotModel& model,
                                const RegistrationObservations& observations,
                                const RegistrationOptions& options, std::vector<std::string>& notes,
                                int& distinct_count) {
  if (Status status = validate_observations(observations, "registration"); !status) {
    return status.error();
  }
  core::KinematicsData data(model);
  EyeObservations result;
  std::vector<Eigen::Vector3d> distinct_origins;
  std::vector<std::string> set_aside;
  std::vector<Eigen::Vector3d> all_points;
  for (std::size_t c = 0; c < observations.configurations.size(); ++c) {
    const ObservedConfiguration& configuration = observations.configurations[c];
    const std::string name = "configuration " + std::to_string(c);
    if (configuration.q.size() != model.dof()) {
      return Error{name + ": " + std::to_string(configuration.q.size()) +
                   " joint values, but robot '" + model.name() + "' has " +
                   std::to_string(model.dof()) + " joints"};
    }
    if (configuration.left_pixels.empty() && configuration.right_pixels.empty()) {
      set_aside.push_back(name + " (seen by neither eye)");
      continue;
    }
    core::forward_kinematics(model, data, configuration.q);
    const Eigen::Isometry3d& T_base_flange = data.T_base_link.back();
    const Eigen::Vector3d origin = T_base_flange.translation();
    bool distinct = true;
    for (std::size_t k = 0; k < distinct_origins.size(); ++k) {
      if ((distinct_origins[k] - origin).norm() < options.min_separation_m) distinct = false;
    }
    if (distinct) {
      distinct_origins.push_back(origin);
    } else {
      set_aside.push_back(name + " (flange within " +
                          std::to_string(static_cast<int>(options.min_separation_m * 1000.0)) +
                          " mm of an earlier configuration; counted once)");
    }
    for (std::size_t i = 0; i < observations.point_in_flange.size(); ++i) {
      const Eigen::Vector3d p_base = T_base_flange * observations.point_in_flange[i];
      all_points.push_back(p_base);
      if (!configuration.left_pixels.empty()) {
        result.left.push_back({p_base, configuration.left_pixels[i], static_cast<int>(c)});
      }
      if (!configuration.right_pixels.empty()) {
        result.right.push_back({p_base, configuration.right_pixels[i], static_cast<int>(c)});
      }
    }
  }
  distinct_count = static_cast<int>(distinct_origins.size());
  notes = set_aside;
  std::string aside;
  for (const std::string& s : set_aside) aside += (aside.empty() ? "" : ", ") + s;
  if (distinct_count < options.min_configurations) {
    return Error{"too few configurations: " + std::to_string(distinct_count) +
                 " distinct usable of " + std::to_string(observations.configurations.size()) +
                 ", need at least " + std::to_string(options.min_configurations) +
                 (aside.empty() ? std::string() : "; set aside: " + aside) +
                 "; add configurations that move the flange to different places"};
  }
  // Collinear points (e.g. one tool-tip point per configuration along one straight line)
  // leave the rotation about that line free.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : all_points) mean += p;
  mean /= static_cast<double>(all_points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : all_points) scatter += (p - mean) * (p - mean).transpose();
  const Eigen::Vector3d spread =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter / all_points.size())
          .eigenvalues()
          .cwiseMax(0.0)
          .cwiseSqrt();
  if (spread[1] < options.min_separation_m) {
    return Error{"degenerate configurations: the observed points lie on one line (spread " +
                 std::to_string(spread[1] * 1000.0) +
                 " mm across it); move the flange off that line in some configurations"};
  }
  return result;
}

}  // namespace

Result<RegistrationResult> register_stereo(const core::RobotModel& model, const CameraModel& left,
                                           const CameraModel& right,
                                           const Eigen::Isometry3d& T_right_left,
                                           const RegistrationObservations& observations,
                                           const RegistrationOptions& options) {
  if (!T_right_left.matrix().allFinite()) return Error{"T_right_left is not finite"};
  RegistrationResult result;
  Result<EyeObservations> collected =
      collect(model, observations, options, result.notes, result.configurations_used);
  if (!collected) return collected.error();
  const EyeObservations& eyes = *collected;
  const Problem problem{&left, &right, T_right_left, &eyes};

  // Initialise from each eye that has enough points; keep the start with the lower cost
  // (three points leave PnP up to four solutions; the other eye decides).
  std::vector<Eigen::Isometry3d> starts;
  if (auto T = pnp(left, eyes.left)) starts.push_back(*T);
  if (auto T = pnp(right, eyes.right)) starts.push_back(T_right_left.inverse() * *T);
  if (starts.empty()) {
    return Error{"cannot initialise: need at least 3 observed points in one eye (left has " +
                 std::to_string(eyes.left.size()) + ", right " + std::to_string(eyes.right.size()) +
                 ")"};
  }
  double best = std::numeric_limits<double>::infinity();
  bool found = false;
  for (const Eigen::Isometry3d& start : starts) {
    const std::vector<double> r = problem.residuals(start);
    if (!r.empty() && cost(r) < best) {
      best = cost(r);
      result.T_left_base = start;
      found = true;
    }
  }
  if (!found) {
    return Error{
        "cannot initialise: the PnP pose puts observed points behind a camera; check "
        "that left and right are not swapped and that T_right_left is the stereo "
        "calibration's"};
  }
  result.initial_left = summarize(left, result.T_left_base, eyes.left);
  result.initial_right = summarize(right, T_right_left * result.T_left_base, eyes.right);
  result.iterations = refine(problem, result.T_left_base, options.max_iterations);
  result.T_right_base = T_right_left * result.T_left_base;
  result.left = summarize(left, result.T_left_base, eyes.left);
  result.right = summarize(right, result.T_right_base, eyes.right);
  return result;
}

StereoResiduals registration_residuals(const core::RobotModel& model, const CameraModel& left,
                                       const CameraModel& right,
                                       const Eigen::Isometry3d& T_left_base,
                                       const Eigen::Isometry3d& T_right_base,
                                       const RegistrationObservations& observations) {
  RegistrationOptions options;
  options.min_configurations = 0;
  options.min_separation_m = 0.0;
  std::vector<std::string> notes;
  int distinct = 0;
  StereoResiduals result;
  Result<EyeObservations> eyes = collect(model, observations, options, notes, distinct);
  if (!eyes) return result;
  result.left = summarize(left, T_left_base, eyes->left);
  result.right = summarize(right, T_right_base, eyes->right);
  return result;
}

RegistrationObservations tool_tip_observations(const core::RobotModel& model,
                                               const std::vector<ToolTipClick>& clicks) {
  RegistrationObservations observations;
  observations.robot = model.name();
  observations.point_in_flange = {model.T_flange_tool().translation()};
  for (const ToolTipClick& click : clicks) {
    ObservedConfiguration configuration;
    configuration.q = click.q;
    if (click.left) configuration.left_pixels = {*click.left};
    if (click.right) configuration.right_pixels = {*click.right};
    observations.configurations.push_back(std::move(configuration));
  }
  return observations;
}

namespace {

// "  left                       412 points  RMS   0.1234 px  max   0.4567 px".
std::string residual_line(const std::string& label, const EyeResiduals& r) {
  std::string text = "  " + label;
  text.append(label.size() < 22 ? 22 - label.size() : 0, ' ');
  return text + " " + core::format_number(r.observations, "%6.0f") + " points  RMS " +
         core::format_number(r.rms_px, "%8.4f") + " px  max " +
         core::format_number(r.max_px, "%8.4f") + " px\n";
}

std::string centre_text(const Eigen::Isometry3d& T_cam_base) {
  const Eigen::Vector3d c = T_cam_base.inverse().translation();
  // Appended piece by piece: GCC 12 warns (-Wrestrict) on a "literal" + string chain here.
  std::string text = "[";
  text += core::format_fixed(c.x(), 4);
  text += ", ";
  text += core::format_fixed(c.y(), 4);
  text += ", ";
  text += core::format_fixed(c.z(), 4);
  text += ']';
  return text;
}

}  // namespace

std::string registration_summary(const RegistrationResult& result) {
  std::string text;
  for (const std::string& note : result.notes) text += "  note: " + note + "\n";
  text += "residuals after the PnP start:\n" + residual_line("left", result.initial_left) +
          residual_line("right", result.initial_right) + "residuals after refinement (" +
          std::to_string(result.iterations) + " Levenberg-Marquardt iterations):\n" +
          residual_line("left", result.left) + residual_line("right", result.right);
  return text + "camera centres in the base frame (m): left " + centre_text(result.T_left_base) +
         ", right " + centre_text(result.T_right_base) + "\n";
}

}  // namespace telear::vision
