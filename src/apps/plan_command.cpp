#include "apps/plan_command.hpp"

#include <nlohmann/json.hpp>
#include <ostream>

#include "apps/command_failure.hpp"
#include "telear/core/plan_hash.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "telear/session/plan_check_report.hpp"
#include "telear/session/plan_collision.hpp"

namespace telear::cli {
int run_plan_check(const PlanCheckOptions& options, std::ostream& out, std::ostream& err) {
  const CommandFailure fail{err, "telear plan check"};
  auto geometry_options = options.geometry_options();
  if (!geometry_options) return fail(geometry_options.error().message);
  auto description = core::load_robot_description(options.robot_spec());
  if (!description) return fail(description.error().message);
  const std::string workspace_file = options.workspace.empty()
                                         ? core::default_workspace_file(description->name)
                                         : options.workspace;
  auto workspace = geometry::load_workspace(workspace_file, options.package_paths);
  if (!workspace) return fail(workspace.error().message);
  auto plan = session::Plan::load(description->model, options.plan);
  if (!plan) return fail(plan.error().message);
  geometry::CollisionSetupOptions setup;
  setup.geometry = *geometry_options;
  if (options.exact_meshes) setup.mesh_collision = geometry::MeshCollision::kExact;
  auto checker = geometry::make_collision_checker(*description, *workspace, setup);
  if (!checker) return fail(checker.error().message);
  auto report = session::check_plan_collisions(*plan, *checker);
  if (!report) return fail(report.error().message);
  const double duration_s = plan->trajectory()->duration();

  out << (options.json ? session::plan_check_json(*report, duration_s)
                       : session::plan_check_text(options.plan, plan->size(), duration_s,
                                                  workspace_file, *report));
  return report->collision_free() ? 0 : 1;
}

int run_plan_hash(const PlanHashOptions& options, std::ostream& out, std::ostream& err) {
  const CommandFailure fail{err, "telear plan hash"};
  auto description = core::load_robot_description(options.robot_spec());
  if (!description) return fail(description.error().message);
  auto plan = session::Plan::load(description->model, options.plan);
  if (!plan) return fail(plan.error().message);
  auto trajectory = plan->trajectory();
  if (!trajectory) return fail(trajectory.error().message);
  auto hash = core::plan_hash(*trajectory);
  if (!hash) return fail(hash.error().message);
  if (!options.json) {
    out << *hash << "\n";
    return 0;
  }
  const nlohmann::json j{{"plan_hash", *hash},
                         {"algorithm", std::string(core::kTrajectoryAlgorithm)},
                         {"duration_s", trajectory->duration()},
                         {"waypoints", plan->size()}};
  out << j.dump(2) << "\n";
  return 0;
}

}  // namespace telear::cli
