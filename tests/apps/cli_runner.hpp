#pragma once
// Runs the real `telear` binary, as a user would, capturing exit code, stdout and stderr.

#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace telear::test {

struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// `arguments` is appended to the binary's path as shell words (quote them yourself).
inline CommandResult run_telear(const std::string& arguments) {
  static int counter = 0;
  const std::string base = ::testing::TempDir() + "telear_cli_" + std::to_string(::getpid()) + "_" +
                           std::to_string(counter++);
  const std::string command =
      std::string(TELEAR_BINARY) + " " + arguments + " > " + base + ".out 2> " + base + ".err";
  const int status = std::system(command.c_str());
  CommandResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = slurp(base + ".out");
  result.err = slurp(base + ".err");
  std::remove((base + ".out").c_str());
  std::remove((base + ".err").c_str());
  return result;
}

}  // namespace telear::test
