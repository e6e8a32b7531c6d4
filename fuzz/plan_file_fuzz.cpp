// Door: a plan file (`plan load FILE`, `telear plan check --plan`: session::Plan::from_yaml),
// for the PUMA 560.

#include "fuzz_input.hpp"
#include "telear/core/robot_loader.hpp"
#include "telear/session/plan.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace telear;
  static const core::RobotModelPtr puma = core::load_robot("puma560").value();
  (void)session::Plan::from_yaml(puma, fuzz::text(data, size), "fuzz_plan.yaml");
  return 0;
}
