#include "telear/session/arm_predictor.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "telear/core/number_format.hpp"

namespace telear::session {

Status ArmPredictorOptions::validate() const {
  if (!(feedback_gain >= 0.0 && feedback_gain <= 1.0)) {
    return Error{"arm predictor: feedback_gain " + core::format_number(feedback_gain) +
                 " must be in [0, 1]"};
  }
  if (!(std::isfinite(max_horizon_s) && max_horizon_s > 0.0)) {
    return Error{"arm predictor: max_horizon_s " + core::format_number(max_horizon_s) +
                 " must be positive and finite"};
  }
  return Status::Ok();
}

std::string ArmPrediction::summary() const {
  if (!available) return "no prediction: " + reason;
  const double feedback_max = feedback.size() > 0 ? feedback.cwiseAbs().maxCoeff() : 0.0;
  return "predicted " + core::format_fixed(horizon_s * 1e3, 0, "ms") + " ahead (Smith feedback " +
         core::format_fixed(feedback_max * 1e3, 2, "mrad") + ")";
}

ArmPredictor::ArmPredictor(ArmPredictorOptions options) : options_(options) {
  assert(options_.validate().ok() && "ArmPredictor: invalid options");
}

void ArmPredictor::follow(core::Trajectory trajectory, std::string id, double started_s) {
  trajectory_.emplace(std::move(trajectory));
  id_ = std::move(id);
  started_s_ = started_s;
}

void ArmPredictor::stop() {
  trajectory_.reset();
  id_.clear();
}

ArmPrediction ArmPredictor::predict(double now_s, const ArmReport& report) const {
  ArmPrediction p;
  const auto impossible = [&p](std::string reason) {
    p.reason = std::move(reason);
    return p;
  };
  const core::RobotState* state = report.state;
  if (state == nullptr) return impossible("no robot state yet");
  // The report's age: how long the arm has moved since (a capture stamp a hair ahead of this
  // clock, from the offset estimate, is no delay).
  p.horizon_s = std::max(0.0, now_s - report.capture_s);
  if (state->estop) return impossible("the robot is e-stopped (" + state->estop_reason + ")");
  if (state->fault) return impossible("fault: " + *state->fault);
  // A controlled stop leaves the plan: where the arm comes to rest is not on it.
  if (state->mode == core::RobotMode::kStopping) {
    return impossible("the robot is stopping (" + state->stop_reason + ")");
  }
  if (!trajectory_) {
    return impossible(state->mode == core::RobotMode::kJogging
                          ? "jogging: no trajectory to predict along"
                          : "no trajectory executing");
  }
  const core::Trajectory& plan = *trajectory_;
  if (state->q.size() != plan.dof() || !state->q.allFinite()) {
    return impossible("the reported joints are not " + std::to_string(plan.dof()) +
                      " finite values");
  }
  if (p.horizon_s > options_.max_horizon_s) {
    return impossible("the state is " + core::format_fixed(p.horizon_s, 2, "s") +
                      " old, beyond the " + core::format_fixed(options_.max_horizon_s, 2, "s") +
                      " the predictor looks ahead");
  }
  // The robot's time into the plan at the report, and now. A report from before the robot
  // took the plan up (another id, or none) shows the arm waiting at its start.
  double report_time = 0.0, now_time = std::max(0.0, now_s - started_s_);
  if (state->trajectory_id == id_) {
    report_time = state->trajectory_time;
    now_time = report_time + p.horizon_s;
  }
  now_time = std::clamp(now_time, 0.0, plan.duration());
  Eigen::VectorXd model_at_report;
  plan.sample(report_time, model_at_report);
  plan.sample(now_time, p.q);
  p.feedback = options_.feedback_gain * (state->q - model_at_report);
  p.q += p.feedback;
  p.plan_time_s = now_time;
  p.gripper = plan.gripper_at(now_time).value_or(state->gripper);
  p.available = true;
  return p;
}

}  // namespace telear::session
