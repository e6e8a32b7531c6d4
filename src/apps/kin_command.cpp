#include "apps/kin_command.hpp"

#include <ostream>

#include "telear/core/ik_analytic.hpp"
#include "telear/core/ik_listing.hpp"
#include "telear/core/joint_values.hpp"
#include "telear/core/kinematics_report.hpp"
#include "telear/core/pose_text.hpp"
#include "telear/core/robot_loader.hpp"

namespace telear::cli {
namespace {

// The target pose from --T or --pose (core/pose_text.hpp).
Result<Eigen::Isometry3d> target_from_options(const KinOptions& options) {
  if (options.T && options.pose) {
    return Error{"give the target as --T or as --pose, not both"};
  }
  if (options.T) return core::rigid_transform_from_text(*options.T, "--T");
  if (options.pose) return core::pose_from_text(*options.pose, "--pose", options.degrees);
  return Error{"needs a target: --T \"16 numbers, row-major\" or --pose x,y,z,roll,pitch,yaw"};
}

// The model, or the one-line error (exit 2).
core::RobotModelPtr load_model(const KinOptions& options, const char* who, std::ostream& err) {
  auto loaded = core::load_robot(options.robot_spec());
  if (!loaded) {
    err << who << loaded.error().message << "\n";
    return nullptr;
  }
  return *loaded;
}

}  // namespace

int run_kin_info(const KinOptions& options, std::ostream& out, std::ostream& err) {
  const core::RobotModelPtr model = load_model(options, "telear kin info: ", err);
  if (!model) return 2;
  out << (options.json ? core::robot_info_json(*model) : core::robot_info_text(*model));
  return 0;
}

int run_kin_fk(const KinOptions& options, std::ostream& out, std::ostream& err) {
  const core::RobotModelPtr model = load_model(options, "telear kin fk: ", err);
  if (!model) return 2;
  auto q = core::parse_joint_values(*model, options.q, "--q", options.degrees);
  if (!q) {
    err << "telear kin fk: " << q.error().message << "\n";
    return 2;
  }
  out << (options.json ? core::forward_kinematics_json(*model, *q)
                       : core::forward_kinematics_text(*model, *q));
  return 0;
}

int run_kin_ik(const KinOptions& options, std::ostream& out, std::ostream& err) {
  const char* who = "telear kin ik: ";
  const core::RobotModelPtr model = load_model(options, who, err);
  if (!model) return 2;
  auto target = target_from_options(options);
  if (!target) {
    err << who << target.error().message << "\n";
    return 2;
  }
  if (Status s = core::check_ik_config(options.config); !s) {
    err << who << "--config: " << s.error().message << "\n";
    return 2;
  }
  if (auto geometry = core::puma_geometry(*model); !geometry && !options.config.empty()) {
    err << who << "--config selects closed-form solutions, and " << geometry.error().message
        << "\n";
    return 2;
  }
  auto listing = core::list_ik_solutions(*model, *target, options.config);
  if (!listing) {
    err << who << listing.error().message << "\n";
    return 1;
  }
  out << (options.json ? core::ik_listing_json(*model, *listing, options.degrees)
                       : core::ik_listing_text(*model, *target, *listing, options.degrees));
  return 0;
}

int run_kin_demo(const KinOptions& options, std::ostream& out, std::ostream& err) {
  const core::RobotModelPtr model = load_model(options, "telear kin demo: ", err);
  if (!model) return 2;
  out << core::kinematics_tour_text(*model);
  return 0;
}

}  // namespace telear::cli
