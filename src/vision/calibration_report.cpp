#include "telear/vision/calibration_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>

#include "telear/core/angles.hpp"
#include "telear/core/image_size.hpp"
#include "telear/core/number_format.hpp"
#include "telear/vision/calibration_file.hpp"
#include "telear/vision/calibration_images.hpp"

namespace telear::vision {
namespace {

// Keys in the order written (the report is read by people too).
using json = nlohmann::ordered_json;

json value_std(double value, double std_dev) {
  return {{"value", value}, {"std", std_dev}};
}

json camera_json(const CameraModel& camera, const IntrinsicsStdDev& sd, double rms_px,
                 std::optional<double> mono_rms_px) {
  json j;
  j["rms_px"] = rms_px;
  if (mono_rms_px) j["mono_rms_px"] = *mono_rms_px;
  j["fx"] = value_std(camera.fx, sd.fx);
  j["fy"] = value_std(camera.fy, sd.fy);
  j["cx"] = value_std(camera.cx, sd.cx);
  j["cy"] = value_std(camera.cy, sd.cy);
  j["alpha_c"] = value_std(camera.alpha_c, 0.0);
  // The model's ROS name, then its coefficients by name in D-vector order (plumb_bob: k1 k2
  // p1 p2 k3; rational_polynomial: ... k4 k5 k6; equidistant: k1 k2 k3 k4).
  j["distortion_model"] = distortion_model_name(camera.kc.model);
  const std::vector<const char*> names = camera.kc.coefficient_names();
  const std::vector<double> values = camera.kc.coefficients();
  const std::vector<double> sds = sd.kc.coefficients();
  for (std::size_t i = 0; i < names.size(); ++i) {
    j[names[i]] = value_std(values[i], i < sds.size() ? sds[i] : 0.0);
  }
  return j;
}

template <int Rows, int Cols>
json matrix_json(const cv::Matx<double, Rows, Cols>& m) {
  json rows = json::array();
  for (int r = 0; r < Rows; ++r) {
    json row = json::array();
    for (int c = 0; c < Cols; ++c) row.push_back(m(r, c));
    rows.push_back(row);
  }
  return rows;
}

json vector_json(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

json rect_json(const cv::Rect& r) {
  return {{"x", r.x}, {"y", r.y}, {"width", r.width}, {"height", r.height}};
}

// One entry per image or pair, used or not, sorted by file name (the input order).
json views_json(const CalibrationReport& report) {
  std::vector<std::pair<std::string, json>> entries;
  auto rejected = [&entries](const RejectedView& v) {
    json j;
    if (v.right_name.empty()) {
      j["image"] = v.name;
    } else {
      j["left"] = v.name;
      j["right"] = v.right_name;
    }
    j["status"] = "rejected";
    j["reason"] = v.reason;
    entries.emplace_back(v.name, j);
  };
  for (const RejectedView& v : report.skipped) rejected(v);
  if (report.mono) {
    for (const RejectedView& v : report.mono->rejected) rejected(v);
    for (const CalibratedView& v : report.mono->views) {
      cv::Mat rvec;
      cv::Mat R(3, 3, CV_64F);
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) R.at<double>(r, c) = v.T_cam_target.linear()(r, c);
      }
      cv::Rodrigues(R, rvec);
      json j;
      j["image"] = v.name;
      j["status"] = "used";
      j["rms_px"] = v.rms_px;
      j["rotation_vector_rad"] = {
          {"value", {rvec.at<double>(0), rvec.at<double>(1), rvec.at<double>(2)}},
          {"std", vector_json(v.rotation_std)}};
      j["translation"] = {{"value", vector_json(v.T_cam_target.translation())},
                          {"std", vector_json(v.translation_std)}};
      entries.emplace_back(v.name, j);
    }
  }
  if (report.stereo) {
    for (const RejectedView& v : report.stereo->rejected) rejected(v);
    for (const StereoCalibratedView& v : report.stereo->views) {
      json j;
      j["left"] = v.left_name;
      j["right"] = v.right_name;
      j["status"] = "used";
      j["rms_px"] = {{"left", v.left_rms_px}, {"right", v.right_rms_px}};
      entries.emplace_back(v.left_name, j);
    }
  }
  std::stable_sort(entries.begin(), entries.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  json views = json::array();
  for (auto& [name, j] : entries) views.push_back(std::move(j));
  return views;
}

std::size_t views_used(const CalibrationReport& report) {
  return report.mono ? report.mono->views.size() : report.stereo->views.size();
}

std::size_t views_rejected(const CalibrationReport& report) {
  return report.skipped.size() +
         (report.mono ? report.mono->rejected.size() : report.stereo->rejected.size());
}

double rotation_angle_deg(const cv::Matx33d& R) {
  cv::Vec3d om;
  cv::Rodrigues(R, om);
  return core::degrees_from_radians(cv::norm(om));
}

// Pads to `width` characters (UTF-8 aware: "±" is one character, two bytes).
std::string padded(std::string text, std::size_t width) {
  std::size_t characters = 0;
  for (const char c : text) characters += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  if (characters < width) text.append(width - characters, ' ');
  return text;
}

// "533.093 ± 0.585", with digits suited to the parameter; "0 (held)" for a fixed one.
std::string value_pm(double value, double std_dev, bool distortion) {
  if (std_dev == 0.0) return core::format_values("%g (held)", value);
  return distortion ? core::format_values("%.5f ± %.5f", value, std_dev)
                    : core::format_values("%.3f ± %.3f", value, std_dev);
}

void parameter_rows(std::string& out, const std::vector<const CameraModel*>& cameras,
                    const std::vector<const IntrinsicsStdDev*>& sds) {
  struct Row {
    const char* name;
    double CameraModel::*value;
    double IntrinsicsStdDev::*sd;
  };
  const Row rows[] = {{"fx [px]", &CameraModel::fx, &IntrinsicsStdDev::fx},
                      {"fy [px]", &CameraModel::fy, &IntrinsicsStdDev::fy},
                      {"cx [px]", &CameraModel::cx, &IntrinsicsStdDev::cx},
                      {"cy [px]", &CameraModel::cy, &IntrinsicsStdDev::cy}};
  for (const Row& row : rows) {
    out += padded(std::string("  ") + row.name, 12);
    for (std::size_t c = 0; c < cameras.size(); ++c) {
      const std::string cell = value_pm(cameras[c]->*row.value, sds[c]->*row.sd, false);
      out += c + 1 < cameras.size() ? padded(cell, 26) : cell;
    }
    out += "\n";
  }
  const std::vector<const char*> names = cameras.front()->kc.coefficient_names();
  for (std::size_t i = 0; i < names.size(); ++i) {
    out += padded(std::string("  ") + names[i], 12);
    for (std::size_t c = 0; c < cameras.size(); ++c) {
      const std::vector<double> value = cameras[c]->kc.coefficients();
      const std::vector<double> sd = sds[c]->kc.coefficients();
      const std::string cell =
          value_pm(i < value.size() ? value[i] : 0.0, i < sd.size() ? sd[i] : 0.0, true);
      out += c + 1 < cameras.size() ? padded(cell, 26) : cell;
    }
    out += "\n";
  }
}

}  // namespace

std::string calibration_report_json(const CalibrationReport& report) {
  assert(report.mono.has_value() != report.stereo.has_value());
  json j;
  j["kind"] = report.mono ? "mono" : "stereo";
  j["pattern"] = report.pattern.spec();
  j["image_size"] = {{"width", report.image_size.width}, {"height", report.image_size.height}};
  j["views_given"] = report.views_given;
  j["views_used"] = views_used(report);
  j["views_rejected"] = views_rejected(report);
  if (report.mono) {
    const MonoCalibration& m = *report.mono;
    j["rms_px"] = m.rms_px;
    j["cameras"]["camera"] = camera_json(m.camera, m.std_dev, m.rms_px, std::nullopt);
  } else {
    const StereoCalibration& s = *report.stereo;
    j["rms_px"] = s.rms_px;
    j["cameras"]["left"] =
        camera_json(s.cameras.left, s.left_std_dev, s.left_rms_px, s.mono_left_rms_px);
    j["cameras"]["right"] =
        camera_json(s.cameras.right, s.right_std_dev, s.right_rms_px, s.mono_right_rms_px);
    cv::Vec3d om;
    cv::Rodrigues(s.R, om);
    json& st = j["stereo"];
    st["units"] = "those of the pattern spacing (metres)";
    st["R"] = matrix_json(s.R);
    st["rotation_vector_rad"] = {{"value", {om[0], om[1], om[2]}},
                                 {"std", vector_json(s.rotation_std)}};
    st["T"] = {{"value", {s.T[0], s.T[1], s.T[2]}}, {"std", vector_json(s.translation_std)}};
    st["baseline"] = value_std(s.baseline(), s.baseline_std);
    st["E"] = matrix_json(s.E);
    st["F"] = matrix_json(s.F);
    st["reordered_pairs"] = report.reordered_pairs;
    const StereoRectification& r = s.rectification;
    st["rectification"] = {{"R1", matrix_json(r.R1)},
                           {"R2", matrix_json(r.R2)},
                           {"P1", matrix_json(r.P1)},
                           {"P2", matrix_json(r.P2)},
                           {"Q", matrix_json(r.Q)},
                           {"left_roi", rect_json(r.left_roi)},
                           {"right_roi", rect_json(r.right_roi)}};
  }
  j["views"] = views_json(report);
  return j.dump(2) + "\n";
}

std::string calibration_summary(const CalibrationReport& report) {
  assert(report.mono.has_value() != report.stereo.has_value());
  const bool stereo = report.stereo.has_value();
  std::string out;
  out += "pattern " + report.pattern.spec() + ", images " +
         core::to_string(core::ImageSize{report.image_size.width, report.image_size.height}) +
         ": " + std::to_string(report.views_given) + (stereo ? " pairs" : " images") + " given, " +
         std::to_string(views_used(report)) + " used, " + std::to_string(views_rejected(report)) +
         " rejected\n";
  const CameraModel& first = stereo ? report.stereo->cameras.left : report.mono->camera;
  out += std::string("lens model ") + distortion_model_name(first.kc.model) + ": D = (";
  const std::vector<const char*> names = first.kc.coefficient_names();
  for (std::size_t i = 0; i < names.size(); ++i) out += (i > 0 ? ", " : "") + std::string(names[i]);
  out += ")\n\n";

  if (stereo) {
    const StereoCalibration& s = *report.stereo;
    out += padded("", 12) + padded("left", 26) + "right\n";
    parameter_rows(out, {&s.cameras.left, &s.cameras.right}, {&s.left_std_dev, &s.right_std_dev});
    out +=
        padded("  RMS", 12) +
        padded(core::format_values("%.3f px (alone %.3f)", s.left_rms_px, s.mono_left_rms_px), 26) +
        core::format_values("%.3f px (alone %.3f)", s.right_rms_px, s.mono_right_rms_px) + "\n\n";
    out += core::format_values(
        "stereo RMS %.3f px (both images); baseline %.6g ± %.2g (pattern units)\n", s.rms_px,
        s.baseline(), s.baseline_std);
    out += core::format_values("  T = (%.6g, %.6g, %.6g)   R: %.4f deg\n", s.T[0], s.T[1], s.T[2],
                               rotation_angle_deg(s.R));
  } else {
    const MonoCalibration& m = *report.mono;
    out += padded("", 12) + "camera\n";
    parameter_rows(out, {&m.camera}, {&m.std_dev});
    out += padded("  RMS", 12) + core::format_values("%.3f px\n", m.rms_px);
  }

  out += "\n";
  const json views = views_json(report);
  out += "  " + padded("view", stereo ? 40 : 31) +
         (stereo ? "left px  right px  status\n" : "rms px  status\n");
  for (const json& v : views) {
    const std::string name = stereo ? file_name_of(v["left"].get<std::string>()) + " + " +
                                          file_name_of(v["right"].get<std::string>())
                                    : file_name_of(v["image"].get<std::string>());
    out += "  " + padded(name, stereo ? 40 : 31);
    if (v["status"] == "used") {
      out += stereo ? core::format_values("%7.3f  %8.3f  used\n", v["rms_px"]["left"].get<double>(),
                                          v["rms_px"]["right"].get<double>())
                    : core::format_values("%6.3f  used\n", v["rms_px"].get<double>());
    } else {
      out += (stereo ? core::format_values("%7s  %8s  ", "-", "-")
                     : core::format_values("%6s  ", "-")) +
             "rejected: " + v["reason"].get<std::string>() + "\n";
    }
  }
  if (stereo && report.reordered_pairs > 0) {
    out += "\n  " + std::to_string(report.reordered_pairs) +
           " pair(s) had the right image's corners numbered from the other end; reordered\n";
  }
  return out;
}

std::vector<std::pair<std::string, std::string>> ros_camera_info_files(
    const std::string& prefix, const CalibrationReport& report) {
  if (prefix.empty()) return {};
  if (report.mono) return {{prefix + ".yaml", ros_mono_camera_info_yaml(*report.mono, "camera")}};
  return {{prefix + "_left.yaml", ros_stereo_camera_info_yaml(*report.stereo, false, "left")},
          {prefix + "_right.yaml", ros_stereo_camera_info_yaml(*report.stereo, true, "right")}};
}

}  // namespace telear::vision
