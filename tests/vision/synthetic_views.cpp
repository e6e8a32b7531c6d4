#include "synthetic_views.hpp"

#include <cstdio>
#include <opencv2/calib3d.hpp>

#include "telear/core/pose.hpp"

namespace telear::test {
namespace {

constexpr double kDeg = M_PI / 180.0;

cv::Mat camera_matrix(const vision::CameraModel& c) {
  return (cv::Mat_<double>(3, 3) << c.fx, 0.0, c.cx, 0.0, c.fy, c.cy, 0.0, 0.0, 1.0);
}

std::vector<cv::Point2d> project_exact(const vision::CameraModel& camera,
                                       const Eigen::Isometry3d& T_cam_target,
                                       const vision::CalibrationPattern& pattern) {
  cv::Mat R(3, 3, CV_64F), rvec, tvec(3, 1, CV_64F);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R.at<double>(r, c) = T_cam_target.linear()(r, c);
    tvec.at<double>(r) = T_cam_target.translation()(r);
  }
  cv::Rodrigues(R, rvec);
  const std::vector<double> kc = camera.kc.coefficients();
  const std::vector<cv::Point3f> object = vision::pattern_object_points(pattern);
  std::vector<cv::Point3d> object_d(object.begin(), object.end());
  std::vector<cv::Point2d> image;
  cv::projectPoints(object_d, rvec, tvec, camera_matrix(camera),
                    cv::Mat(1, static_cast<int>(kc.size()), CV_64F, const_cast<double*>(kc.data())),
                    image);
  return image;
}

bool inside(const vision::CameraModel& camera, const Eigen::Isometry3d& T_cam_target,
            const vision::CalibrationPattern& pattern, double margin) {
  for (const cv::Point3f& p : vision::pattern_object_points(pattern)) {
    const Eigen::Vector3d q = T_cam_target * Eigen::Vector3d(p.x, p.y, p.z);
    if (q.z() < 0.1) return false;
    // Stay well inside the distortion model's monotonic range.
    if (std::hypot(q.x() / q.z(), q.y() / q.z()) > 0.6) return false;
  }
  for (const cv::Point2d& uv : project_exact(camera, T_cam_target, pattern)) {
    if (uv.x < margin || uv.y < margin || uv.x > camera.width - 1 - margin ||
        uv.y > camera.height - 1 - margin) {
      return false;
    }
  }
  return true;
}

}  // namespace

SyntheticRig default_rig() {
  SyntheticRig rig;
  vision::CameraModel& left = rig.left;
  left.width = 640;
  left.height = 480;
  left.fx = 800.0;
  left.fy = 802.5;
  left.cx = 321.7;
  left.cy = 238.4;
  left.kc = vision::Distortion::plumb_bob(-0.3, 0.1, 0.0012, -0.0008, 0.0);
  vision::CameraModel& right = rig.right;
  right.width = 640;
  right.height = 480;
  right.fx = 806.0;
  right.fy = 804.8;
  right.cx = 316.2;
  right.cy = 243.9;
  right.kc = vision::Distortion::plumb_bob(-0.29, 0.095, -0.0006, 0.0009, 0.0);
  // Right camera centre 6 cm along the left camera's x axis (plus a little y, z), turned
  // about 1 degree: X_R = R (X_L - c) with c the right centre in the left frame.
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.8 * kDeg, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(-0.4 * kDeg, Eigen::Vector3d::UnitX()) *
                             Eigen::AngleAxisd(0.3 * kDeg, Eigen::Vector3d::UnitZ()))
                                .toRotationMatrix();
  const Eigen::Vector3d centre(0.06, 0.0008, -0.0012);
  rig.T_right_left = Eigen::Isometry3d::Identity();
  rig.T_right_left.linear() = R;
  rig.T_right_left.translation() = -R * centre;
  rig.right.T_cam_base = rig.T_right_left;
  return rig;
}

std::vector<Eigen::Isometry3d> random_pattern_poses(const SyntheticRig& rig,
                                                    const vision::CalibrationPattern& pattern,
                                                    int count, std::mt19937_64& rng,
                                                    double margin_px) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d centre_target((pattern.cols - 1) * pattern.spacing / 2.0,
                                      (pattern.rows - 1) * pattern.spacing / 2.0, 0.0);
  std::vector<Eigen::Isometry3d> poses;
  for (int attempt = 0; attempt < 100000 && static_cast<int>(poses.size()) < count; ++attempt) {
    const double z = 0.35 + 0.3 * unit(rng);
    const double u = rig.left.width * (0.2 + 0.6 * unit(rng));
    const double v = rig.left.height * (0.2 + 0.6 * unit(rng));
    const Eigen::Vector3d centre_cam((u - rig.left.cx) / rig.left.fx * z,
                                     (v - rig.left.cy) / rig.left.fy * z, z);
    // Tilted 30 to 50 degrees about a random axis in the pattern plane, turned up to 20
    // degrees in that plane: every view carries perspective (Zhang's method needs it).
    const double azimuth = 2.0 * M_PI * unit(rng);
    const double tilt = (30.0 + 20.0 * unit(rng)) * kDeg;
    const Eigen::Matrix3d R =
        (Eigen::AngleAxisd((unit(rng) - 0.5) * 40.0 * kDeg, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(tilt, Eigen::Vector3d(std::cos(azimuth), std::sin(azimuth), 0.0)))
            .toRotationMatrix();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = R;
    T.translation() = centre_cam - R * centre_target;
    if (inside(rig.left, T, pattern, margin_px) &&
        inside(rig.right, rig.T_right_left * T, pattern, margin_px)) {
      poses.push_back(T);
    }
  }
  return poses;
}

std::vector<cv::Point2f> project_pattern(const vision::CameraModel& camera,
                                         const Eigen::Isometry3d& T_cam_target,
                                         const vision::CalibrationPattern& pattern, double noise_px,
                                         std::mt19937_64& rng) {
  std::normal_distribution<double> noise(0.0, noise_px);
  std::vector<cv::Point2f> points;
  for (const cv::Point2d& uv : project_exact(camera, T_cam_target, pattern)) {
    const double dx = noise_px > 0.0 ? noise(rng) : 0.0;
    const double dy = noise_px > 0.0 ? noise(rng) : 0.0;
    points.emplace_back(static_cast<float>(uv.x + dx), static_cast<float>(uv.y + dy));
  }
  return points;
}

std::vector<vision::StereoPatternView> stereo_views(const SyntheticRig& rig,
                                                    const vision::CalibrationPattern& pattern,
                                                    const std::vector<Eigen::Isometry3d>& poses,
                                                    double noise_px, std::mt19937_64& rng) {
  std::vector<vision::StereoPatternView> views;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "view%02zu", i);
    views.push_back(
        {std::string(name) + "_left", std::string(name) + "_right",
         project_pattern(rig.left, poses[i], pattern, noise_px, rng),
         project_pattern(rig.right, rig.T_right_left * poses[i], pattern, noise_px, rng)});
  }
  return views;
}

}  // namespace telear::test
