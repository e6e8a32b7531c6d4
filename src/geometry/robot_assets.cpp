#include "telear/geometry/robot_assets.hpp"

namespace telear::geometry {

Result<core::MarkerMount> RobotAssets::marker() const {
  if (description.marker) return *description.marker;
  return Error{"robot '" + description.name + "' (" + description.source +
               ") has no registration marker: add `marker:` to its robot file or a " +
               description.name + ".marker.yaml beside it (docs/registration.md)"};
}

Result<RobotAssets> load_robot_assets(const core::RobotSpec& spec, const GeometryOptions& options) {
  auto description = core::load_robot_description(spec);
  if (!description) return description.error();
  auto body = body_for(*description, options);
  if (!body) return body.error();
  RobotAssets assets;
  assets.description = std::move(description).value();
  assets.body = std::move(body->body);
  assets.warnings = std::move(body->warnings);
  return assets;
}

}  // namespace telear::geometry
