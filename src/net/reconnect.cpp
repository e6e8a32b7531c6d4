#include "telear/net/reconnect.hpp"

#include <algorithm>
#include <cmath>

namespace telear::net {

BackoffSchedule BackoffSchedule::from(const ClientOptions& options) {
  return {options.reconnect_initial_backoff_s, options.reconnect_backoff_factor,
          options.reconnect_max_backoff_s};
}

double BackoffSchedule::delay_s(int n) const {
  const double grown = initial_s * std::pow(factor, std::max(0, n));
  return std::min(std::isfinite(grown) ? grown : max_s, max_s);
}

}  // namespace telear::net
