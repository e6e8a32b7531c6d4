#pragma once
// Approximate-time pairing of two streams by their stamps: the left and the right camera's
// images, in the manner of message_filters' ApproximateTime for two topics. A pair is a left
// and a right message that are each other's nearest in stamp and no further apart than a
// tolerance; a message that has no such partner is dropped and counted. Standard library only
// and C++17: the ROS unit (ros1_camera_link.cpp, C++17) uses it, the C++20 tests test it.
//
// When a pair is final. Stamps grow on each stream. Take the older of the two queue heads,
// say the left x (x <= y, the right head). Every later right is later than y, so y is x's
// nearest right. x is y's nearest left unless a later left comes nearer to y:
//   - y - x > tolerance: x can never pair; it is dropped.
//   - a left x2 is queued after x: x is y's nearest when |x2 - y| >= y - x, else x is dropped
//     (x2 then pairs with y, or a later right).
//   - no left is queued after x: the next one comes at least one frame period after x, so
//     when y - x <= half the stream's shortest recent frame period it cannot be nearer and the
//     pair is made at once; otherwise the pair waits for that next left. Synchronised cameras
//     (equal stamps) and free-running ones (at most half a frame apart) never wait.
//
// A stamp older than its stream's previous one (a bag played again, simulated time reset)
// starts both streams afresh; a repeated stamp is dropped. A stream whose partner is silent
// keeps at most max_queue messages (the oldest dropped).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <utility>
#include <vector>

namespace telear::drivers::ros1 {

template <typename T>
class StampPairing {
 public:
  struct Pair {
    T left, right;
    std::int64_t left_stamp_ns = 0, right_stamp_ns = 0;
  };

  // tolerance_ns: the largest |left stamp - right stamp| of a pair (>= 0).
  explicit StampPairing(std::int64_t tolerance_ns, std::size_t max_queue = 8)
      : tolerance_ns_(tolerance_ns), max_queue_(std::max<std::size_t>(max_queue, 2)) {}

  // Adds one message of the left (right = false) or right stream; returns the pairs it
  // completes, oldest first.
  std::vector<Pair> add(bool right, std::int64_t stamp_ns, T message) {
    std::vector<Pair> pairs;
    Stream& s = stream(right);
    if (s.has_last && stamp_ns == s.last_stamp) {
      ++s.dropped;
      return pairs;
    }
    if (s.has_last && stamp_ns < s.last_stamp) restart();
    if (s.has_last) {
      s.periods.push_back(stamp_ns - s.last_stamp);
      if (s.periods.size() > kPeriods) s.periods.pop_front();
    }
    s.has_last = true;
    s.last_stamp = stamp_ns;
    s.queue.push_back(Entry{stamp_ns, std::move(message)});
    if (s.queue.size() > max_queue_) drop_head(s);
    match(pairs);
    return pairs;
  }

  // Messages dropped unpaired, per stream, since the start.
  std::uint64_t dropped(bool right) const { return right ? right_.dropped : left_.dropped; }
  // Times the stamps went back and both streams started afresh.
  std::uint64_t restarts() const { return restarts_; }

 private:
  static constexpr std::size_t kPeriods = 8;

  struct Entry {
    std::int64_t stamp;
    T message;
  };
  struct Stream {
    std::deque<Entry> queue;
    std::deque<std::int64_t> periods;  // the last intervals between consecutive stamps
    std::int64_t last_stamp = 0;
    bool has_last = false;
    std::uint64_t dropped = 0;

    // The shortest recent frame period; 0 before two messages.
    std::int64_t min_period() const {
      return periods.empty() ? 0 : *std::min_element(periods.begin(), periods.end());
    }
  };

  Stream& stream(bool right) { return right ? right_ : left_; }

  void drop_head(Stream& s) {
    s.queue.pop_front();
    ++s.dropped;
  }

  void restart() {
    ++restarts_;
    for (Stream* s : {&left_, &right_}) {
      s->dropped += s->queue.size();
      s->queue.clear();
      s->periods.clear();
      s->has_last = false;
    }
  }

  void match(std::vector<Pair>& pairs) {
    while (!left_.queue.empty() && !right_.queue.empty()) {
      const bool left_older = left_.queue.front().stamp <= right_.queue.front().stamp;
      Stream& a = left_older ? left_ : right_;  // holds the older head, x
      Stream& b = left_older ? right_ : left_;  // holds y, x's nearest partner
      const std::int64_t x = a.queue.front().stamp;
      const std::int64_t y = b.queue.front().stamp;
      const std::int64_t gap = y - x;
      if (gap > tolerance_ns_) {
        drop_head(a);
        continue;
      }
      if (a.queue.size() > 1) {
        const std::int64_t x2 = a.queue[1].stamp;
        const std::int64_t gap2 = x2 > y ? x2 - y : y - x2;
        if (gap2 < gap) {
          drop_head(a);
          continue;
        }
      } else if (gap != 0) {
        const std::int64_t period = a.min_period();
        if (period <= 0 || 2 * gap > period) break;  // a nearer x may come: wait for it
      }
      Entry& ex = a.queue.front();
      Entry& ey = b.queue.front();
      Pair pair{left_older ? std::move(ex.message) : std::move(ey.message),
                left_older ? std::move(ey.message) : std::move(ex.message), left_older ? x : y,
                left_older ? y : x};
      a.queue.pop_front();
      b.queue.pop_front();
      pairs.push_back(std::move(pair));
    }
  }

  std::int64_t tolerance_ns_;
  std::size_t max_queue_;
  Stream left_, right_;
  std::uint64_t restarts_ = 0;
};

}  // namespace telear::drivers::ros1
