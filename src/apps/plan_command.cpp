#include "apps/plan_command.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <ostream>
#include <utility>

#include "telear/core/robot_description.hpp"
#include "telear/core/workspace.hpp"
#include "telear/geometry/workspace_meshes.hpp"
#include "telear/session/plan_collision.hpp"

namespace telear::cli {
namespace {

std::string millimetres(double metres) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f mm", metres * 1e3);
  return buffer;
}

std::string seconds(double s) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3f s", s);
  return buffer;
}

nlohmann::json report_json(const geometry::TrajectoryCheckReport& r, double duration_s) {
  nlohmann::json j;
  j["collision_free"] = r.collision_free();
  j["collisions"] = nlohmann::json::array();
  for (const geometry::PlanCollision& c : r.collisions) {
    j["collisions"].push_back({{"time_s", c.time_s},
                               {"link", c.body},
                               {"object", c.other},
                               {"self", c.self},
                               {"depth_m", c.depth_m},
                               {"segment", c.segment}});
  }
  const auto clearance = [](const geometry::PlanClearance& m) {
    return nlohmann::json{{"distance_m", std::isfinite(m.distance_m) ? nlohmann::json(m.distance_m)
                                                                     : nlohmann::json(nullptr)},
                          {"time_s", m.time_s},
                          {"segment", m.segment},
                          {"link", m.body},
                          {"object", m.other},
                          {"self", m.self}};
  };
  j["min_clearance"] = clearance(r.min_clearance);
  j["min_clearance_m"] = j["min_clearance"]["distance_m"];
  j["min_workspace_clearance"] = clearance(r.min_workspace_clearance);
  j["duration_s"] = duration_s;
  j["configurations_checked"] = r.evaluations;
  return j;
}

}  // namespace

int run_plan_check(const PlanCheckOptions& options, std::ostream& out, std::ostream& err) {
  const auto fail = [&err](const std::string& message) {
    err << "telear plan check: " << message << "\n";
    return 2;
  };
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
  auto checker = geometry::make_collision_checker(*description, *workspace, setup);
  if (!checker) return fail(checker.error().message);
  auto report = session::check_plan_collisions(*plan, *checker);
  if (!report) return fail(report.error().message);
  const double duration_s = plan->trajectory()->duration();

  if (options.json) {
    out << report_json(*report, duration_s).dump(2) << "\n";
    return report->collision_free() ? 0 : 1;
  }
  out << "plan " << options.plan << " (" << plan->size() << " waypoints, " << seconds(duration_s)
      << ") in " << workspace_file << ": "
      << (report->collision_free() ? "collision-free" : "COLLISION") << "\n";
  for (const geometry::PlanCollision& c : report->collisions) {
    out << "  contact at " << seconds(c.time_s) << " (segment " << c.segment << "): " << c.body
        << " with " << (c.self ? "link " : "") << c.other << ", depth " << millimetres(c.depth_m)
        << "\n";
  }
  for (const auto& [what, m] :
       {std::pair{"min clearance", report->min_clearance},
        std::pair{"min clearance to the workspace", report->min_workspace_clearance}}) {
    if (!std::isfinite(m.distance_m)) continue;
    out << "  " << what << " " << millimetres(m.distance_m) << " at " << seconds(m.time_s) << ": "
        << m.body << " to " << (m.self ? "link " : "") << m.other << "\n";
  }
  return report->collision_free() ? 0 : 1;
}

}  // namespace telear::cli
