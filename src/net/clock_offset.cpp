#include "telear/net/clock_offset.hpp"

#include <algorithm>

namespace telear::net {

bool ClockOffsetEstimator::add(const PingSample& s) {
  if (s.client_receive_ns < s.client_send_ns || s.server_send_ns < s.server_receive_ns) {
    return false;
  }
  ClockOffset sample;
  sample.offset_ns =
      ((s.server_receive_ns - s.client_send_ns) + (s.server_send_ns - s.client_receive_ns)) / 2;
  sample.delay_ns =
      (s.client_receive_ns - s.client_send_ns) - (s.server_send_ns - s.server_receive_ns);
  sample.delay_ns = std::max<std::int64_t>(sample.delay_ns, 0);
  sample.error_bound_ns = sample.delay_ns / 2;
  recent_.push_back(sample);
  while (recent_.size() > window_) recent_.pop_front();
  return true;
}

std::optional<ClockOffset> ClockOffsetEstimator::estimate() const {
  if (recent_.empty()) return std::nullopt;
  ClockOffset best = *std::min_element(
      recent_.begin(), recent_.end(),
      [](const ClockOffset& a, const ClockOffset& b) { return a.delay_ns < b.delay_ns; });
  best.samples = recent_.size();
  return best;
}

std::int64_t ClockOffsetEstimator::to_client_ns(std::int64_t server_ns) const {
  const auto e = estimate();
  return e ? server_ns - e->offset_ns : server_ns;
}

std::int64_t ClockOffsetEstimator::to_server_ns(std::int64_t client_ns) const {
  const auto e = estimate();
  return e ? client_ns + e->offset_ns : client_ns;
}

}  // namespace telear::net
