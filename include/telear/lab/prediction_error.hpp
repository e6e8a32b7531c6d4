#pragma once
// The predicted arm measured against the simulator's truth (issue 23; `telear bench prediction`
// and the demo's delay window): at each displayed frame, the tool position the view drew --
// the predicted arm when it drew one, otherwise the last reported state, which is what a view
// without prediction shows -- and the reported state's, each against where the simulated arm
// truly was when the view was updated.
//
//   error_predicted   = | p_tool(q_drawn) - p_tool(q_true) |     q_drawn: prediction.q when
//   error_unpredicted = | p_tool(q_reported) - p_tool(q_true) |  show_prediction, else q_reported
//
// Tool positions by the nominal model's forward kinematics (the joints the simulator reports
// are the nominal model's readings), in mm; percentiles nearest-rank (net::percentile).

#include <Eigen/Core>
#include <vector>

#include "telear/core/robot_model.hpp"
#include "telear/session/session.hpp"

namespace telear::lab {

struct PredictionErrorSummary {
  int frames = 0;               // frames measured
  int frames_predicted = 0;     // ... of which the view drew a predicted arm
  double horizon_ms_p50 = 0.0;  // how far ahead it predicted (the state's age), frames predicted
  double predicted_mm_p50 = 0.0, predicted_mm_p95 = 0.0, predicted_mm_max = 0.0;
  double unpredicted_mm_p50 = 0.0, unpredicted_mm_p95 = 0.0, unpredicted_mm_max = 0.0;
};

class PredictionErrorSeries {
 public:
  // `model` must outlive the series.
  explicit PredictionErrorSeries(const core::RobotModel& model) : model_(&model) {}

  // One displayed frame: the session's view after its update, and the simulator's joints at
  // that update. A view without a reported state (or joints of another size) is not counted.
  void add(const session::SessionView& view, const Eigen::VectorXd& true_q);

  int frames() const { return static_cast<int>(predicted_mm_.size()); }
  PredictionErrorSummary summary() const;

 private:
  const core::RobotModel* model_;
  std::vector<double> predicted_mm_, unpredicted_mm_, horizon_ms_;
};

}  // namespace telear::lab
