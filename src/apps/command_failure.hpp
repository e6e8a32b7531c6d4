#pragma once
// How a command says that it failed (docs/cli.md): one line "telear SUB: what is wrong" on
// stderr and the exit status, 2 for input it refuses and 1 for a failure while it ran. Every
// command reports through this one helper, so the line reads the same everywhere:
//   const CommandFailure fail{err, "telear register"};
//   if (!model) return fail("--robot: " + model.error().message);  // prints it, returns 2

#include <ostream>
#include <string>
#include <string_view>
#include <utility>

namespace telear::cli {

inline constexpr int kExitBadInput = 2;
inline constexpr int kExitFailure = 1;

class CommandFailure {
 public:
  CommandFailure(std::ostream& err, std::string command)
      : err_(err), command_(std::move(command)) {}

  // Writes "<command>: <message>" as one line and returns `code`.
  int operator()(std::string_view message, int code = kExitBadInput) const {
    err_ << command_ << ": " << message << "\n";
    return code;
  }

 private:
  std::ostream& err_;
  std::string command_;
};

}  // namespace telear::cli
