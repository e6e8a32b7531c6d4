#pragma once
// The time source of the simulation, in seconds as a double from an arbitrary epoch.
//
// SteadyClock is real time (std::chrono::steady_clock, counted from the clock's
// construction): what the robot server's servo thread uses. ManualClock is simulated time
// that only moves when its owner advances it: tests drive the robot through seconds of motion
// in microseconds of real time, and get the same result on every run.
//
// A double holds seconds since the epoch to well under a nanosecond for days, far finer than
// the servo period (1 ms), and it is the unit Trajectory and TimedWaypoints already use.

#include <atomic>
#include <chrono>

namespace telear::sim {

class SimClock {
 public:
  virtual ~SimClock() = default;
  // Seconds since the clock's epoch; never decreases. Safe to call from any thread.
  virtual double now() const = 0;
};

class SteadyClock final : public SimClock {
 public:
  SteadyClock();
  double now() const override;

 private:
  std::chrono::steady_clock::time_point epoch_;
};

class ManualClock final : public SimClock {
 public:
  explicit ManualClock(double start = 0.0);
  double now() const override;
  // Moves time forward by dt >= 0 seconds (asserts on a negative or non-finite dt).
  void advance(double dt);
  // Sets the time; t must not be earlier than now() (asserts).
  void set(double t);

 private:
  std::atomic<double> now_;
};

}  // namespace telear::sim
