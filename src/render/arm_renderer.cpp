#include "telear/render/arm_renderer.hpp"

#include <cassert>

namespace telear::render {

Result<ArmRenderer> ArmRenderer::create(const core::ArmBody& body) {
  std::vector<const core::Mesh*> meshes;
  for (const core::BodyPart& part : body.parts) meshes.push_back(&part.mesh);
  auto parts = MeshSetRenderer::create(meshes);
  if (!parts) return Error{"arm renderer: " + parts.error().message};
  ArmRenderer r;
  r.parts_ = std::move(parts.value());
  return r;
}

core::PartRange ArmRenderer::update(core::ArmBodyPose& pose) {
  assert(pose.part_count() == parts_.part_count() &&
         "ArmRenderer::update(): the pose belongs to another body");
  const core::PartRange range = pose.changed();
  matrices_uploaded_ += parts_.set_matrices(pose.T_base_part(), range);
  pose.clear_changes();
  return range;
}

}  // namespace telear::render
