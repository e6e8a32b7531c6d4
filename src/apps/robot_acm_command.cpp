#include "apps/robot_acm_command.hpp"

#include <fstream>
#include <ostream>

#include "apps/command_failure.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/geometry/allowed_collisions_file.hpp"

namespace telear::cli {

int run_robot_acm(const RobotAcmOptions& options, std::ostream& out, std::ostream& err) {
  const CommandFailure fail{err, "telear robot acm"};
  auto geometry_options = options.geometry_options();
  if (!geometry_options) return fail(geometry_options.error().message);
  auto description = core::load_robot_description(options.robot_spec());
  if (!description) return fail(description.error().message);
  geometry::CollisionSetupOptions setup;
  setup.geometry = *geometry_options;
  setup.allowed.samples = options.samples;
  setup.allowed.seed = options.seed;
  setup.allowed.allow_never = options.never;
  setup.allowed.allow_constant = options.constant;
  setup.allowed.constant_tolerance_m = options.constant_tolerance_m;
  // The matrix is the links' own, stored for both checks: found on the meshes, not the hulls.
  setup.mesh_collision = geometry::MeshCollision::kExact;
  auto matrix = geometry::sample_allowed_collisions(*description, setup);
  if (!matrix) return fail(matrix.error().message);
  const std::string block =
      geometry::allowed_collisions_block(*matrix, description->name, setup.allowed);
  if (options.output.empty()) {
    out << block;
  } else {
    std::ofstream file(options.output);
    if (!(file << block) || !file.flush()) {
      return fail("cannot write '" + options.output + "'");
    }
    out << "wrote " << matrix->pairs().size() << " allowed pairs of " << description->name << " to "
        << options.output << "\n";
  }
  // A DH table (no URDF links) has no `allowed_collisions:` key: its matrix is sampled at load.
  if (description->links.empty()) {
    err << "telear robot acm: note: " << description->name
        << " is a DH table; only a URDF robot file stores allowed_collisions:\n";
  }
  return 0;
}

}  // namespace telear::cli
