#pragma once
// A latest-wins slot: the hand-over between two pipeline stages that never queues.
//
// The producer put()s each new item; it replaces whatever the consumer has not taken yet
// (that item is dropped and counted). The consumer takes the newest item, waiting for one
// newer than the last it saw. So a slow consumer skips items instead of lagging behind, and
// a fast producer is never blocked by a slow consumer: put() only swaps under a mutex.
//
// Items are numbered by put() from 1; a consumer remembers the number it last took and asks
// for anything newer, which lets several consumers share one slot (each skips on its own):
// the slot keeps the newest item only, it does not consume it.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>

namespace telear::net {

template <typename T>
class LatestSlot {
 public:
  struct Taken {
    std::shared_ptr<const T> item;
    std::uint64_t number = 0;   // put() count of this item, from 1
    std::uint64_t skipped = 0;  // items put after `after` and before this one (never seen)
  };

  // Publishes `item` as the newest; wakes every waiting consumer.
  void put(T item) {
    auto shared = std::make_shared<const T>(std::move(item));
    {
      std::lock_guard lock(mutex_);
      latest_ = std::move(shared);
      ++number_;
    }
    changed_.notify_all();
  }

  // The newest item if it is newer than `after` (0: any), without waiting.
  std::optional<Taken> try_take(std::uint64_t after = 0) const {
    std::lock_guard lock(mutex_);
    return take_locked(after);
  }

  // Waits up to `timeout` for an item newer than `after`; nullopt on timeout or close().
  std::optional<Taken> wait_take(std::uint64_t after, std::chrono::nanoseconds timeout) const {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, timeout, [&] { return closed_ || number_ > after; });
    if (closed_) return std::nullopt;
    return take_locked(after);
  }

  // Wakes every waiter for good (shutdown); later waits return at once.
  void close() {
    {
      std::lock_guard lock(mutex_);
      closed_ = true;
    }
    changed_.notify_all();
  }

  bool closed() const {
    std::lock_guard lock(mutex_);
    return closed_;
  }

  std::uint64_t count() const {
    std::lock_guard lock(mutex_);
    return number_;
  }

 private:
  std::optional<Taken> take_locked(std::uint64_t after) const {
    if (number_ <= after || !latest_) return std::nullopt;
    const std::uint64_t skipped = after == 0 ? 0 : number_ - after - 1;
    return Taken{latest_, number_, skipped};
  }

  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::shared_ptr<const T> latest_;
  std::uint64_t number_ = 0;
  bool closed_ = false;
};

}  // namespace telear::net
