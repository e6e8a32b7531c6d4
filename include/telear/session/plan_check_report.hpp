#pragma once
// What `telear plan check` prints about a saved plan's collision check (plan_collision.hpp):
// text for the operator -- the verdict, every contact with its time, segment, link, object and
// depth, and the smallest clearances -- and JSON for scripts (SI units, 2-space indent,
// trailing newline).

#include <cstddef>
#include <string>

#include "telear/geometry/trajectory_collision.hpp"

namespace telear::session {

// "plan p.yaml (9 waypoints, 6.120 s) in ws.yaml: COLLISION\n  contact at 1.230 s
// (segment 2): link6 with table_top, depth 4.2 mm\n  min clearance to the workspace ...", then
// "  nearest of the arm's own links ..." where a pair of the arm's own links is nearer than the
// workspace (their gaps at the joints, a contact between them listed as any other).
std::string plan_check_text(const std::string& plan_file, std::size_t waypoints, double duration_s,
                            const std::string& workspace_file,
                            const geometry::TrajectoryCheckReport& report);

// collision_free, collisions[] (time_s, link, object, self, depth_m, segment),
// min_workspace_clearance and min_clearance (over every pair, the arm's own included;
// distance_m: null when nothing was measured), min_clearance_m (= min_workspace_clearance's
// distance_m: the figure the safety margin applies to, as in the demo report), duration_s,
// configurations_checked.
std::string plan_check_json(const geometry::TrajectoryCheckReport& report, double duration_s);

}  // namespace telear::session
