#include "apps/robot_arguments.hpp"

namespace telear::cli {

Result<geometry::GeometryOptions> RobotArguments::geometry_options() const {
  geometry::GeometryOptions options;
  options.package_paths = package_paths;
  if (missing_meshes == "error") {
    options.missing_meshes = geometry::MissingMeshes::kError;
  } else if (missing_meshes == "primitives") {
    options.missing_meshes = geometry::MissingMeshes::kPrimitives;
  } else {
    return Error{"--missing-meshes: '" + missing_meshes + "' is not error or primitives"};
  }
  return options;
}

}  // namespace telear::cli
