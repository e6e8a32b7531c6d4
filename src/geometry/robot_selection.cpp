#include "telear/geometry/robot_selection.hpp"

namespace telear::geometry {

Result<GeometryOptions> RobotSelection::geometry_options() const {
  GeometryOptions options;
  options.package_paths = package_paths;
  if (missing_meshes == "error") {
    options.missing_meshes = MissingMeshes::kError;
  } else if (missing_meshes == "primitives") {
    options.missing_meshes = MissingMeshes::kPrimitives;
  } else {
    return Error{"missing_meshes: '" + missing_meshes + "' is not error or primitives"};
  }
  return options;
}

}  // namespace telear::geometry
