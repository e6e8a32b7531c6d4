#include "telear/net/lease_manager.hpp"

#include "telear/core/number_format.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <utility>

#include "telear/core/clock.hpp"
#include "telear/net/random_token.hpp"

#include "steady_time.hpp"

namespace telear::net {

namespace {

std::string milliseconds_whole(std::int64_t ns) {
  return core::format_fixed(static_cast<double>(ns) * 1e-6, 0, "ms");
}

}  // namespace

void LeaseOptions::set_default_heartbeat(std::int64_t ns) {
  default_heartbeat_ns = ns;
  min_heartbeat_ns = std::min(min_heartbeat_ns, ns);
  max_heartbeat_ns = std::max(max_heartbeat_ns, ns);
}

LeaseManager::LeaseManager(LeaseOptions options, LapseHandler on_lapse)
    : options_(options), on_lapse_(std::move(on_lapse)) {
  watchdog_ = std::thread([this] { watch(); });
}

LeaseManager::~LeaseManager() {
  stop();
}

void LeaseManager::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  if (watchdog_.joinable()) watchdog_.join();
}

std::int64_t LeaseManager::granted_heartbeat_ns(std::int64_t requested_ns) const {
  if (requested_ns <= 0) requested_ns = options_.default_heartbeat_ns;
  return std::clamp(requested_ns, options_.min_heartbeat_ns, options_.max_heartbeat_ns);
}

Result<LeaseGrant> LeaseManager::acquire(const std::string& holder,
                                         std::int64_t requested_heartbeat_ns) {
  std::unique_lock lock(mutex_);
  const std::int64_t now = core::monotonic_ns();
  if (lease_ && lease_->expires_ns > now) {
    return Error{"the lease is held by '" + lease_->holder +
                 "'; wait until it is released or lapses (it is renewed every " +
                 milliseconds_whole(lease_->heartbeat_ns) + ")"};
  }
  LeaseGrant grant;
  grant.lease_id = random_token(16);
  grant.holder = holder;
  grant.heartbeat_ns = granted_heartbeat_ns(requested_heartbeat_ns);
  grant.expires_ns = now + grant.heartbeat_ns;
  lease_ = grant;
  lock.unlock();
  changed_.notify_all();
  return grant;
}

Result<std::string> LeaseManager::check_locked(const std::string& lease_id,
                                               std::int64_t now_ns) const {
  if (lease_id.empty()) return Error{"no lease id: acquire the lease first"};
  if (lease_ && lease_->lease_id == lease_id) {
    if (lease_->expires_ns <= now_ns) {
      return Error{"the lease of '" + lease_->holder + "' lapsed: not renewed within " +
                   milliseconds_whole(lease_->heartbeat_ns)};
    }
    return lease_->holder;
  }
  if (!lapsed_id_.empty() && lapsed_id_ == lease_id) {
    return Error{
        "the lease lapsed (not renewed within its heartbeat period) and the arm was "
        "stopped; acquire it again"};
  }
  if (lease_) return Error{"not the current lease: the lease is held by '" + lease_->holder + "'"};
  return Error{"not the current lease: nobody holds the lease; acquire it first"};
}

Result<LeaseGrant> LeaseManager::renew(const std::string& lease_id) {
  std::unique_lock lock(mutex_);
  const std::int64_t now = core::monotonic_ns();
  auto holder = check_locked(lease_id, now);
  if (!holder) return holder.error();
  lease_->expires_ns = now + lease_->heartbeat_ns;
  LeaseGrant grant = *lease_;
  lock.unlock();
  changed_.notify_all();
  return grant;
}

Result<std::string> LeaseManager::release(const std::string& lease_id) {
  std::unique_lock lock(mutex_);
  auto holder = check_locked(lease_id, core::monotonic_ns());
  if (!holder) return holder.error();
  lease_.reset();
  lock.unlock();
  changed_.notify_all();
  return holder;
}

Result<std::string> LeaseManager::check(const std::string& lease_id) const {
  std::lock_guard lock(mutex_);
  return check_locked(lease_id, core::monotonic_ns());
}

std::string LeaseManager::holder() const {
  std::lock_guard lock(mutex_);
  return lease_ ? lease_->holder : std::string();
}

std::optional<LeaseLapse> LeaseManager::last_lapse() const {
  std::lock_guard lock(mutex_);
  return last_lapse_;
}

void LeaseManager::watch() {
  std::unique_lock lock(mutex_);
  while (!stopping_) {
    if (!lease_) {
      changed_.wait(lock);
      continue;
    }
    const std::int64_t expires = lease_->expires_ns;
    if (core::monotonic_ns() < expires) {
      // Woken early by a renewal or release (notify) or at the expiry.
      changed_.wait_until(lock, steady_time(expires));
      continue;
    }
    LeaseLapse lapse{lease_->holder, expires, 0};
    lapsed_id_ = lease_->lease_id;
    lease_.reset();
    lapse.stop_started_ns = core::monotonic_ns();
    last_lapse_ = lapse;
    lock.unlock();
    on_lapse_(lapse);
    lock.lock();
  }
}

}  // namespace telear::net
