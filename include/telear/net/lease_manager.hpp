#pragma once
// The lease: exactly one operator commands the arm at a time, and only while it keeps
// proving it is alive (the dead-man).
//
// A holder acquires the lease with a heartbeat period P (its wish, clamped to the server's
// bounds [min, max]; 0 asks for the default) and gets a random lease id it passes with every
// command. Each renewal moves the expiry to now + P. A watchdog thread sleeps until the
// current expiry; when it passes without renewal the lease lapses: the holder is cleared and
// the lapse handler is called at once on the watchdog thread, which makes the controlled
// stop. The delay from the expiry to the handler is the thread's wake-up latency (well under
// a millisecond on an idle machine, a few milliseconds under load), far inside the 200 ms
// the dead-man allows.
//
// Errors (a Result message) say why: held by someone else (and since when), a stale id, a
// lapsed lease. All times are the server's monotonic clock in ns (telear/core/clock.hpp).

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "telear/core/result.hpp"

namespace telear::net {

struct LeaseOptions {
  std::int64_t default_heartbeat_ns = 250'000'000;
  std::int64_t min_heartbeat_ns = 50'000'000;
  std::int64_t max_heartbeat_ns = 5'000'000'000;

  // The default period `ns` (> 0), the bounds widened to admit it when it lies outside.
  void set_default_heartbeat(std::int64_t ns);
};

struct LeaseGrant {
  std::string lease_id;  // 32 hex digits (random_token, telear/net/random_token.hpp)
  std::string holder;    // the client's name
  std::int64_t heartbeat_ns = 0;
  std::int64_t expires_ns = 0;
};

struct LeaseLapse {
  std::string holder;
  std::int64_t expired_ns = 0;       // when the lease ran out
  std::int64_t stop_started_ns = 0;  // when the lapse handler (the controlled stop) began
};

class LeaseManager {
 public:
  using LapseHandler = std::function<void(const LeaseLapse&)>;

  // Starts the watchdog. `on_lapse` runs on the watchdog thread, without the manager's lock.
  LeaseManager(LeaseOptions options, LapseHandler on_lapse);
  ~LeaseManager();  // stop()
  LeaseManager(const LeaseManager&) = delete;
  LeaseManager& operator=(const LeaseManager&) = delete;

  // Stops the watchdog (no lapse is handled after this); idempotent.
  void stop();

  const LeaseOptions& options() const { return options_; }
  // The period granted for a wish (0: the default), clamped to [min, max].
  std::int64_t granted_heartbeat_ns(std::int64_t requested_ns) const;

  Result<LeaseGrant> acquire(const std::string& holder, std::int64_t requested_heartbeat_ns);
  Result<LeaseGrant> renew(const std::string& lease_id);
  // Gives the lease back; returns who held it.
  Result<std::string> release(const std::string& lease_id);
  // Succeeds with the holder's name when `lease_id` is the current lease.
  Result<std::string> check(const std::string& lease_id) const;

  std::string holder() const;  // empty when free
  std::optional<LeaseLapse> last_lapse() const;

 private:
  Result<std::string> check_locked(const std::string& lease_id, std::int64_t now_ns) const;
  void watch();

  const LeaseOptions options_;
  const LapseHandler on_lapse_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<LeaseGrant> lease_;
  std::optional<LeaseLapse> last_lapse_;
  std::string lapsed_id_;  // the last lapsed lease, so its holder is told why
  bool stopping_ = false;
  std::thread watchdog_;
};

}  // namespace telear::net
