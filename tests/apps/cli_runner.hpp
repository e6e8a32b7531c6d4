#pragma once
// Runs the real `telear` binary, as a user would, capturing exit code, stdout and stderr.

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "test_util/temp_dir.hpp"

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
  const test_files::TempDir dir("cli");
  const std::string out = dir.file("stdout"), err = dir.file("stderr");
  const std::string command =
      std::string(TELEAR_BINARY) + " " + arguments + " > " + out + " 2> " + err;
  const int status = std::system(command.c_str());
  CommandResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = slurp(out);
  result.err = slurp(err);
  return result;
}

}  // namespace telear::test
