// Door: a URDF's text, as `--robot arm.urdf` reads it (core::parse_urdf: urdfdom, then the
// chain, limits and frames) and as a robot server's GetInfo hands it over
// (core::parse_urdf_description). No mesh file is read on this door.

#include "fuzz_input.hpp"
#include "telear/core/robot_description.hpp"
#include "telear/core/robot_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace telear;
  const std::string text = fuzz::text(data, size);
  (void)core::parse_urdf(text, "fuzz.urdf");
  (void)core::parse_urdf_description(text, "fuzz.urdf");
  return 0;
}
