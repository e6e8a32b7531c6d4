#include "telear/lab/prediction_error.hpp"

#include <algorithm>

#include "telear/core/kinematics.hpp"
#include "telear/net/latency_summary.hpp"

namespace telear::lab {

void PredictionErrorSeries::add(const session::SessionView& view, const Eigen::VectorXd& true_q) {
  const int dof = model_->dof();
  if (!view.real || view.real->state.q.size() != dof || true_q.size() != dof) return;
  const Eigen::VectorXd& reported = view.real->state.q;
  const Eigen::VectorXd& drawn = view.show_prediction ? view.prediction.q : reported;
  const Eigen::Vector3d truth = core::tool_pose(*model_, true_q).translation();
  predicted_mm_.push_back(1e3 * (core::tool_pose(*model_, drawn).translation() - truth).norm());
  unpredicted_mm_.push_back(1e3 *
                            (core::tool_pose(*model_, reported).translation() - truth).norm());
  if (view.show_prediction) horizon_ms_.push_back(1e3 * view.prediction.horizon_s);
}

PredictionErrorSummary PredictionErrorSeries::summary() const {
  PredictionErrorSummary s;
  s.frames = frames();
  s.frames_predicted = static_cast<int>(horizon_ms_.size());
  if (s.frames == 0) return s;
  s.horizon_ms_p50 = net::percentile(horizon_ms_, 50);
  s.predicted_mm_p50 = net::percentile(predicted_mm_, 50);
  s.predicted_mm_p95 = net::percentile(predicted_mm_, 95);
  s.predicted_mm_max = *std::max_element(predicted_mm_.begin(), predicted_mm_.end());
  s.unpredicted_mm_p50 = net::percentile(unpredicted_mm_, 50);
  s.unpredicted_mm_p95 = net::percentile(unpredicted_mm_, 95);
  s.unpredicted_mm_max = *std::max_element(unpredicted_mm_.begin(), unpredicted_mm_.end());
  return s;
}

}  // namespace telear::lab
