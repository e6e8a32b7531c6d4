#include "telear/session/plan_check_report.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <utility>

#include "telear/core/number_format.hpp"

#include "seconds.hpp"

namespace telear::session {
namespace {

std::string millimetres(double metres) {
  return core::format_fixed(metres * 1e3, 1, "mm");
}

nlohmann::json clearance_json(const geometry::PlanClearance& m) {
  return nlohmann::json{{"distance_m", std::isfinite(m.distance_m) ? nlohmann::json(m.distance_m)
                                                                   : nlohmann::json(nullptr)},
                        {"time_s", m.time_s},
                        {"segment", m.segment},
                        {"link", m.body},
                        {"object", m.other},
                        {"self", m.self}};
}

}  // namespace

std::string plan_check_text(const std::string& plan_file, std::size_t waypoints, double duration_s,
                            const std::string& workspace_file,
                            const geometry::TrajectoryCheckReport& report) {
  std::ostringstream out;
  out << "plan " << plan_file << " (" << waypoints << " waypoints, " << seconds(duration_s)
      << ") in " << workspace_file << ": "
      << (report.collision_free() ? "collision-free" : "COLLISION") << "\n";
  for (const geometry::PlanCollision& c : report.collisions) {
    out << "  contact at " << seconds(c.time_s) << " (segment " << c.segment << "): " << c.body
        << " with " << (c.self ? "link " : "") << c.other << ", depth " << millimetres(c.depth_m)
        << "\n";
  }
  // The workspace's clearance first: the figure the safety margin applies to. The arm's own
  // nearest pair follows only where it is nearer (its by-design gaps at the joints usually are:
  // the PUMA's wrist 2.0 mm); it matters as a contact, which is listed above.
  const geometry::PlanClearance& w = report.min_workspace_clearance;
  if (std::isfinite(w.distance_m)) {
    out << "  min clearance to the workspace " << millimetres(w.distance_m) << " at "
        << seconds(w.time_s) << ": " << w.body << " to " << w.other << "\n";
  }
  const geometry::PlanClearance& a = report.min_clearance;
  if (std::isfinite(a.distance_m) && a.self) {
    out << "  nearest of the arm's own links " << millimetres(a.distance_m) << " at "
        << seconds(a.time_s) << ": " << a.body << " to link " << a.other << "\n";
  }
  return out.str();
}

std::string plan_check_json(const geometry::TrajectoryCheckReport& report, double duration_s) {
  nlohmann::json j;
  j["collision_free"] = report.collision_free();
  j["collisions"] = nlohmann::json::array();
  for (const geometry::PlanCollision& c : report.collisions) {
    j["collisions"].push_back({{"time_s", c.time_s},
                               {"link", c.body},
                               {"object", c.other},
                               {"self", c.self},
                               {"depth_m", c.depth_m},
                               {"segment", c.segment}});
  }
  // min_clearance_m is the operator's figure, the workspace's (as the demo report's): the
  // nearest pair over every pair, the arm's own included, is min_clearance.
  j["min_workspace_clearance"] = clearance_json(report.min_workspace_clearance);
  j["min_clearance_m"] = j["min_workspace_clearance"]["distance_m"];
  j["min_clearance"] = clearance_json(report.min_clearance);
  j["duration_s"] = duration_s;
  j["configurations_checked"] = report.evaluations;
  return j.dump(2) + "\n";
}

}  // namespace telear::session
