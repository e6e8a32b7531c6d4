// Door: a robot's DH table (`--robot arm.yaml`, core::parse_dh_yaml) and its body file
// (core::parse_body_yaml, read against the PUMA 560's model). The first byte picks which.

#include "fuzz_input.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/core/robot_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace telear;
  static const core::RobotModelPtr puma = core::load_robot("puma560").value();
  const auto [door, text] = fuzz::door_input(data, size, 2);
  if (door == 0) {
    (void)core::parse_dh_yaml(text, "fuzz.yaml");
  } else {
    (void)core::parse_body_yaml(text, "fuzz_body.yaml", *puma);
  }
  return 0;
}
