#pragma once
// `telear record`: a passive observer of running servers, recording their streams to MCAP
// (record::SessionRecorder; docs/recording.md). It takes no lease: it reads the robot's state
// (with the lease holder's ghost), the stereo stream as received, and the servers' info.

#include <ostream>
#include <string>

namespace telear::cli {

struct RecordOptions {
  std::string robot_server;   // HOST:PORT
  std::string vision_server;  // HOST:PORT; empty: no video recorded
  std::string token_file;     // the servers' bearer token (first line)
  std::string tls_ca_file;    // the servers speak TLS: trust this CA (PEM)
  std::string output;         // the .mcap file
  double seconds = 0.0;       // 0: until interrupted (SIGINT, SIGTERM)
  double state_rate_hz = 50.0;
};

// Exit 0 when the file is complete, 1 when recording failed, 2 on bad options.
int run_record(const RecordOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
