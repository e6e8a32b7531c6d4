// telear's command line. CLI11 is included in this translation unit only (it is slow to
// compile); each subcommand's work lives in its own *_command.cpp without CLI11.

#include <CLI/CLI.hpp>
#include <iostream>

#include "apps/kin_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"telear: augmented-reality telerobotics (docs/cli.md)", "telear"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "telear 0.1.0");

  // [SECTION] kin
  telear::cli::KinOptions kin;
  CLI::App* kin_app = app.add_subcommand("kin", "the arm's geometric model: FK, IK, limits");
  kin_app->require_subcommand(1);
  auto add_robot = [&kin](CLI::App* sub) {
    sub->add_option("--robot", kin.robot, "shipped robot name or .yaml / .urdf file")
        ->capture_default_str();
  };
  CLI::App* kin_info = kin_app->add_subcommand("info", "joints, limits, named configurations");
  add_robot(kin_info);
  kin_info->add_flag("--json", kin.json, "print JSON");
  CLI::App* kin_fk = kin_app->add_subcommand("fk", "forward kinematics: tool pose and frames");
  add_robot(kin_fk);
  kin_fk->add_option("--q", kin.q, "joint values q1,...,qn (rad, or deg with --deg) or a name")
      ->required();
  kin_fk->add_flag("--deg", kin.degrees, "joint values in degrees");
  kin_fk->add_flag("--json", kin.json, "print JSON (row-major 4x4, metres)");
  CLI::App* kin_demo = kin_app->add_subcommand("demo", "FK at the named configurations");
  add_robot(kin_demo);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  if (kin_info->parsed()) return telear::cli::run_kin_info(kin, std::cout, std::cerr);
  if (kin_fk->parsed()) return telear::cli::run_kin_fk(kin, std::cout, std::cerr);
  if (kin_demo->parsed()) return telear::cli::run_kin_demo(kin, std::cout, std::cerr);
  return 1;
}
