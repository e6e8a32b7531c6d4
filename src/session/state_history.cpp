#include "telear/session/state_history.hpp"

#include <algorithm>
#include <cmath>

namespace telear::session {

void StateHistory::add(double capture_s, const Eigen::VectorXd& q, double gripper) {
  if (!states_.empty() && capture_s <= states_.back().t) return;
  states_.push_back({capture_s, q, gripper});
  while (states_.size() > 1 && states_.front().t < capture_s - span_s_) states_.pop_front();
}

std::optional<ArmAt> StateHistory::at(double t, double tolerance_s) const {
  if (states_.empty()) return std::nullopt;
  const auto after = std::upper_bound(states_.begin(), states_.end(), t,
                                      [](double time, const Entry& e) { return time < e.t; });
  if (after == states_.begin()) {
    if (states_.front().t - t > tolerance_s) return std::nullopt;
    return ArmAt{states_.front().q, states_.front().gripper};
  }
  const Entry& a = *std::prev(after);
  if (after == states_.end() || a.t == t) {
    if (t - a.t > tolerance_s) return std::nullopt;
    return ArmAt{a.q, a.gripper};
  }
  const Entry& b = *after;
  if (a.q.size() != b.q.size()) return std::nullopt;
  const double s = (t - a.t) / (b.t - a.t);
  return ArmAt{a.q + s * (b.q - a.q), s < 0.5 ? a.gripper : b.gripper};
}

std::optional<ArmAt> StateHistory::nearest(double t) const {
  const Entry* best = nullptr;
  for (const Entry& e : states_) {
    if (best == nullptr || std::abs(e.t - t) < std::abs(best->t - t)) best = &e;
  }
  if (best == nullptr) return std::nullopt;
  return ArmAt{best->q, best->gripper};
}

bool StateHistory::moving_near(double t, const Eigen::VectorXd& q, double window_s,
                               double tolerance_rad) const {
  for (const Entry& e : states_) {
    if (std::abs(e.t - t) <= window_s && e.q.size() == q.size() &&
        (e.q - q).cwiseAbs().maxCoeff() > tolerance_rad) {
      return true;
    }
  }
  return false;
}

}  // namespace telear::session
