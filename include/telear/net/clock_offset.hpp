#pragma once
// Estimates the offset between a server's monotonic clock and this machine's, from Ping
// exchanges (the NTP on-wire calculation), so latencies across hosts are meaningful.
//
// One exchange: the client sends at t0 (client clock), the server receives at t1 and replies
// at t2 (server clock), the client receives at t3. With symmetric paths
//   offset = server - client = ((t1 - t0) + (t2 - t3)) / 2,   delay = (t3 - t0) - (t2 - t1),
// and the error of one sample is at most delay / 2. Queues make paths asymmetric in bursts,
// so the estimate is the offset of the sample with the smallest delay among the last
// `window` samples (NTP's clock filter): the least-queued exchange is the most symmetric.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>

namespace telear::net {

struct PingSample {
  std::int64_t client_send_ns = 0;     // t0
  std::int64_t server_receive_ns = 0;  // t1
  std::int64_t server_send_ns = 0;     // t2
  std::int64_t client_receive_ns = 0;  // t3
};

struct ClockOffset {
  std::int64_t offset_ns = 0;       // server clock minus client clock
  std::int64_t delay_ns = 0;        // round trip minus the server's processing time
  std::int64_t error_bound_ns = 0;  // delay / 2: the offset is within +- this
  std::size_t samples = 0;
};

class ClockOffsetEstimator {
 public:
  explicit ClockOffsetEstimator(std::size_t window = 16) : window_(window == 0 ? 1 : window) {}

  // Adds one exchange; samples with t3 < t0 or t2 < t1 (corrupt) are ignored and return false.
  bool add(const PingSample& sample);
  // The current estimate; nullopt before the first valid sample.
  std::optional<ClockOffset> estimate() const;

  // Converts a server timestamp to this machine's clock (identity before any sample).
  std::int64_t to_client_ns(std::int64_t server_ns) const;
  std::int64_t to_server_ns(std::int64_t client_ns) const;

 private:
  std::size_t window_;
  std::deque<ClockOffset> recent_;
};

}  // namespace telear::net
