#include "telear/session/ghost_clearance.hpp"

#include <algorithm>
#include <cmath>

#include "telear/core/number_format.hpp"

namespace telear::session {

std::string ClearanceState::summary() const {
  using core::format_number;
  if (level == Level::kUnchecked) return "not checked";
  if (!contacts.empty()) {
    const geometry::Contact& c = contacts.front();
    return "contact: " + c.body + " and " + c.other + " (" +
           format_number(c.depth_m * 1e3, "%.1f") + " mm deep)";
  }
  if (!std::isfinite(workspace.distance_m)) return "no workspace to check against";
  return "clearance " + format_number(workspace.distance_m * 1e3, "%.0f") +
         " mm: " + workspace.body + " and " + workspace.other;
}

GhostClearance::GhostClearance(geometry::CollisionChecker& checker, double safety_margin_m)
    : checker_(&checker), safety_margin_m_(safety_margin_m) {
  state_.safety_margin_m = safety_margin_m;
}

const ClearanceState& GhostClearance::update(const Eigen::VectorXd& q, double gripper_fraction) {
  if (state_.level != ClearanceState::Level::kUnchecked && q.size() == last_q_.size() &&
      q == last_q_ && gripper_fraction == last_gripper_) {
    return state_;
  }
  last_q_ = q;
  last_gripper_ = gripper_fraction;
  geometry::CollisionReport report = checker_->check(q, gripper_fraction);
  ClearanceState state;
  state.safety_margin_m = safety_margin_m_;
  state.contacts = std::move(report.contacts);
  // check()'s minimum is over every pair; the arm's own pairs are often the nearest, so the
  // workspace's minimum is looked for among the body-object pairs when it is not that one.
  if (!report.min_clearance.self) {
    state.workspace = report.min_clearance;
  } else {
    checker_->set_configuration(q, gripper_fraction);
    for (const geometry::CollisionPair& pair : checker_->pairs()) {
      if (pair.other_object < 0) continue;
      const geometry::PairDistance d = checker_->distance(pair);
      if (d.distance_m <= 0.0 || d.distance_m >= state.workspace.distance_m) continue;
      state.workspace.distance_m = d.distance_m;
      state.workspace.body = checker_->robot().bodies[pair.body].name;
      state.workspace.other = checker_->pair_other_name(pair);
      state.workspace.self = false;
      state.workspace.p_body_base = d.p_body_base;
      state.workspace.p_other_base = d.p_other_base;
    }
  }
  const auto& bodies = checker_->robot().bodies;
  for (const geometry::Contact& c : state.contacts) {
    for (const std::string& name : {c.body, c.self ? c.other : std::string()}) {
      const int index = name.empty() ? -1 : checker_->robot().body_index(name);
      if (index >= 0) state.contact_frames.push_back(bodies[index].frame);
    }
  }
  std::sort(state.contact_frames.begin(), state.contact_frames.end());
  state.contact_frames.erase(std::unique(state.contact_frames.begin(), state.contact_frames.end()),
                             state.contact_frames.end());
  state.level = !state.contacts.empty() ? ClearanceState::Level::kContact
                : state.workspace.distance_m < safety_margin_m_
                    ? ClearanceState::Level::kWithinMargin
                    : ClearanceState::Level::kClear;
  state_ = std::move(state);
  return state_;
}

}  // namespace telear::session
