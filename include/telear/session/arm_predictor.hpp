#pragma once
// The predictive display (Bejczy's phantom robot, 1990; Smith's predictor, 1957): where the
// real arm is *now*, when everything the operator sees of it -- the video and the robot's
// state -- arrives late.
//
// The model is the trajectory the robot executes (the plan the session sent). A state the
// robot reported at its own time t_r into that trajectory, captured at c (this machine's
// clock, s), is d = now - c old. The arm has gone on along the plan for d more seconds, so
//
//   model now:        q_model(now) = traj(t_r + d)                        (clamped to the plan)
//   model at report:  q_model(c)   = traj(t_r)
//   Smith feedback:   e            = q_reported(c) - q_model(c)           (the delayed error)
//   prediction:       q_pred(now)  = q_model(now) + feedback_gain * e
//
// With no delay (d = 0) the prediction is the reported state; with a perfect model (the arm
// on its plan) e = 0 and the prediction is the plan at the arm's true time; a model error
// that changes slowly against d (an arm lagging its plan, a servo gain under 1) is what e
// carries across the delay.
//
// Before the robot's first report of the trajectory (it left before the delay let one
// through), the robot's time into it is estimated from when the session sent it:
// t = now - started_s, and e = q_reported - traj(0) (the arm waiting at the plan's start). An
// uplink delay (the command's own way to the robot) is not known to this machine and makes
// that estimate early by as much; the robot's first report corrects it.
//
// Prediction is impossible -- the prediction says why, and the view falls back to the AR / VR
// rule of display_mode.hpp -- without a state, on an e-stop or a fault, while the robot is
// stopping, with no trajectory executing (idle, a jog) and beyond max_horizon_s.
//
// Pure logic fed with times (seconds on one clock), no threads and no clock of its own: tests
// drive it with made-up reports. Units: rad or m per joint.

#include <Eigen/Core>
#include <optional>
#include <string>

#include "telear/core/result.hpp"
#include "telear/core/robot_state.hpp"
#include "telear/core/trajectory.hpp"

namespace telear::session {

struct ArmPredictorOptions {
  double feedback_gain = 1.0;  // of the Smith term, in [0, 1]; 0: the model alone
  double max_horizon_s = 5.0;  // a state older than this is not predicted across, > 0

  // Errors name the field and the range.
  Status validate() const;
};

struct ArmPrediction {
  bool available = false;
  std::string reason;        // why there is no prediction (empty when available)
  double horizon_s = 0.0;    // how far ahead of the report it predicts: now - capture time
  double plan_time_s = 0.0;  // the trajectory's time predicted for now
  Eigen::VectorXd q;         // the arm now (empty when not available)
  double gripper = 1.0;      // 0 closed .. 1 open: the plan's last command, else the report's
  Eigen::VectorXd feedback;  // feedback_gain * e, per joint (empty when not available)
  // One line for a status panel: "predicted 402 ms ahead (Smith feedback 0.10 mrad)" or
  // "no prediction: <reason>".
  std::string summary() const;
};

// One reported state as the predictor needs it.
struct ArmReport {
  const core::RobotState* state = nullptr;  // null: no state yet
  double capture_s = 0.0;                   // when it was captured, this machine's clock
};

class ArmPredictor {
 public:
  // options must validate() (asserted).
  explicit ArmPredictor(ArmPredictorOptions options = {});

  const ArmPredictorOptions& options() const { return options_; }

  // The robot executes `trajectory` under `id` (RobotState::trajectory_id), started at
  // `started_s` on this machine's clock (when it was accepted: the session takes the middle of
  // the request's round trip).
  void follow(core::Trajectory trajectory, std::string id, double started_s);
  // No trajectory executing any more (completed, cancelled, aborted).
  void stop();
  bool following() const { return trajectory_.has_value(); }

  // The arm at `now_s` from the newest report.
  ArmPrediction predict(double now_s, const ArmReport& report) const;

 private:
  ArmPredictorOptions options_;
  std::optional<core::Trajectory> trajectory_;
  std::string id_;
  double started_s_ = 0.0;
};

}  // namespace telear::session
