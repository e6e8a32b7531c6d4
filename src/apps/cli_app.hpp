#pragma once
// telear's command line in pieces: one registration function per subcommand family adds its
// options to the CLI11 app and appends what each parsed subcommand runs; main() parses and
// runs the one that was chosen. CLI11 is slow to compile: only main.cpp, cli_commands.cpp and
// cli_conventions.cpp include it (this header forward-declares its types).
//
// Conventions (docs/cli.md): every usage error (unknown subcommand or option, missing value
// or required option, a refused value) prints ONE line "telear SUB: what is wrong" on stderr
// and exits 2; --help and --version print to stdout and exit 0.

#include <functional>
#include <ostream>
#include <vector>

#include "telear/core/image_size.hpp"
#include "telear/geometry/robot_selection.hpp"

namespace CLI {
class App;
class ParseError;
class Validator;
}  // namespace CLI

namespace telear::cli {

// A subcommand and what it runs once parsed (the handler owns the parsed options).
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};
using Commands = std::vector<Command>;

void add_demo_command(CLI::App& app, Commands& commands);
void add_kin_commands(CLI::App& app, Commands& commands);  // kin info | fk | demo | ik
void add_render_command(CLI::App& app, Commands& commands);
void add_plan_commands(CLI::App& app, Commands& commands);         // plan check
void add_robot_commands(CLI::App& app, Commands& commands);        // robot acm
void add_calibration_commands(CLI::App& app, Commands& commands);  // calibrate, register, eval
void add_sim_commands(CLI::App& app, Commands& commands);  // sim capture | frame | observations
void add_console_command(CLI::App& app, Commands& commands);
void add_web_command(CLI::App& app, Commands& commands);     // web (the browser operator)
void add_replay_command(CLI::App& app, Commands& commands);  // replay (a recording's AR view)
void add_record_command(CLI::App& app, Commands& commands);  // record (MCAP)
void add_report_command(CLI::App& app, Commands& commands);  // report (plots of a recording)
void add_bench_commands(CLI::App& app, Commands& commands);  // bench render | kin | stream

// --robot, --tip, --package-path (repeatable) and, when the command draws the arm,
// --missing-meshes: the same four options on every command that takes a robot. The console,
// whose --robot is the robot server's address, names the arm with `robot_option` "--arm".
void add_robot_arguments(CLI::App* app, geometry::RobotSelection& arguments, bool draws_meshes,
                         const std::string& robot_option = "--robot");

// The one WIDTHxHEIGHT validator (core::parse_image_size) for every option that takes a
// size; with `list`, comma-separated sizes. Refused: "--resolution: '20x10' is outside ...".
CLI::Validator image_size_validator(core::ImageSize min, core::ImageSize max, bool list = false);

// What a CLI11 parse error becomes: help and version go to `out` (exit 0); anything else is a
// usage error: one line on `err` naming the subcommand and the problem, exit 2.
int report_parse_error(const CLI::App& app, const CLI::ParseError& error, std::ostream& out,
                       std::ostream& err);

}  // namespace telear::cli
