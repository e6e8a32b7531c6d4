#include "telear/core/ik_listing.hpp"

#include <string>
#include <utility>

#include "telear/core/ik_branches.hpp"
#include "telear/core/ik_ur.hpp"
#include "telear/core/inverse_kinematics.hpp"

namespace telear::core {

Result<IkListing> list_ik_solutions(const RobotModel& model, const Eigen::Isometry3d& T_base_tool,
                                    std::string_view config) {
  IkListing listing;
  AnalyticIkResult& result = listing.result;
  auto geometry = puma_geometry(model);
  if (geometry) {
    listing.closed_form = true;
    result = solve_analytic_ik(model, *geometry, T_base_tool, config);
    if (result.status == IkStatus::kUnreachable) return Error{result.message};
    return listing;
  }
  auto ur = ur_geometry(model);
  if (ur) {
    // Only the branches that exist (up to 8), each FK-checked.
    listing.closed_form = true;
    result = solve_ur_analytic_ik(model, *ur, T_base_tool, config);
    if (result.status == IkStatus::kUnreachable) return Error{result.message};
    return listing;
  }
  if (!config.empty()) {
    return Error{"config selects closed-form solutions, and " + geometry.error().message + "; " +
                 ur.error().message};
  }
  if (model.dof() == 6) {
    auto branches = solve_ik_all(model, T_base_tool);
    if (!branches) return branches.error();
    result.solutions = std::move(branches).value();
  } else {
    auto solution = solve_ik_nearest(model, T_base_tool, Eigen::VectorXd::Zero(model.dof()));
    if (!solution) return solution.error();
    result.solutions.push_back(std::move(solution).value());
  }
  if (result.solutions.empty()) return Error{"no solution found for the pose (unreachable?)"};
  if (result.solutions.front().singular) {
    result.status = IkStatus::kSingular;
    result.message = "near a singularity (smallest Jacobian singular value below 1e-6)";
  }
  return listing;
}

}  // namespace telear::core
