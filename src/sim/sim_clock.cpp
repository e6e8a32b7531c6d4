#include "telear/sim/sim_clock.hpp"

#include <cassert>
#include <cmath>

namespace telear::sim {

SteadyClock::SteadyClock() : epoch_(std::chrono::steady_clock::now()) {}

double SteadyClock::now() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - epoch_).count();
}

ManualClock::ManualClock(double start) : now_(start) {
  assert(std::isfinite(start) && "ManualClock: start time is not finite");
}

double ManualClock::now() const {
  return now_.load();
}

void ManualClock::advance(double dt) {
  assert(std::isfinite(dt) && dt >= 0.0 && "ManualClock::advance(): dt must be finite and >= 0");
  // Only the test's own thread advances the clock, but readers may run concurrently.
  double current = now_.load();
  while (!now_.compare_exchange_weak(current, current + dt)) {
  }
}

void ManualClock::set(double t) {
  assert(std::isfinite(t) && t >= now_.load() && "ManualClock::set(): time cannot go back");
  now_.store(t);
}

}  // namespace telear::sim
