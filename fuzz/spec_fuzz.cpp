// Door: the one-line specs of the command line and the console: a console script
// (console::parse_ui_script, 6 joints), a registration target (`--target`,
// vision::parse_registration_target) and a calibration pattern (`--pattern`,
// vision::parse_calibration_pattern). The first byte picks which.

#include "fuzz_input.hpp"
#include "telear/console/ui_script.hpp"
#include "telear/vision/calibration_pattern.hpp"
#include "telear/vision/registration_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace telear;
  const auto [door, text] = fuzz::door_input(data, size, 3);
  switch (door) {
    case 0:
      (void)console::parse_ui_script(text, 6, "fuzz_script.txt");
      break;
    case 1:
      (void)vision::parse_registration_target(text);
      break;
    default:
      (void)vision::parse_calibration_pattern(text);
      break;
  }
  return 0;
}
