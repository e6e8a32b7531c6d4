#include "telear/net/token_file.hpp"

#include <fstream>

namespace telear::net {

Result<std::string> load_token_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) return Error{"cannot read the token file '" + path + "'"};
  std::string line;
  std::getline(in, line);
  const char* space = " \t\r\n\v\f";
  const auto first = line.find_first_not_of(space);
  if (first == std::string::npos) {
    return Error{"the token file '" + path + "' holds no token (first line)"};
  }
  const auto last = line.find_last_not_of(space);
  return line.substr(first, last - first + 1);
}

}  // namespace telear::net
