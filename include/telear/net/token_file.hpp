#pragma once
// The bearer token read from a file (--token-file of the servers, the console and the capture;
// the vision server's token for the robot server): one reading and one set of messages for
// every reader. The token itself travels as telear/net/bearer_auth.hpp describes.

#include <string>

#include "telear/core/result.hpp"

namespace telear::net {

// The token from a token file: its first line, surrounding white space (and a Windows line
// end) trimmed. Errors: "cannot read the token file 'PATH'", "the token file 'PATH' holds no
// token (first line)".
Result<std::string> load_token_file(const std::string& path);

}  // namespace telear::net
