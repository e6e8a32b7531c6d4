#include "telear/sim/servo_thread.hpp"

#include <cassert>
#include <chrono>

namespace telear::sim {

ServoThread::ServoThread(SimulatedRobot& robot, double period) : robot_(robot), period_(period) {
  assert(period > 0.0 && "ServoThread: period must be positive");
  thread_ = std::thread([this] { run(); });
}

ServoThread::~ServoThread() {
  stop();
}

void ServoThread::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void ServoThread::run() {
  using clock = std::chrono::steady_clock;
  const auto period =
      std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(period_));
  auto next = clock::now();
  std::unique_lock lock(mutex_);
  while (!stopping_) {
    lock.unlock();
    robot_.update();
    lock.lock();
    next += period;
    // After a long stall, re-anchor instead of running a burst of back-to-back updates.
    if (const auto now = clock::now(); next < now) next = now;
    wake_.wait_until(lock, next, [this] { return stopping_; });
  }
}

}  // namespace telear::sim
