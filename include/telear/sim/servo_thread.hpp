#pragma once
// A thread that calls SimulatedRobot::update() every `period` seconds of real time: the
// servo loop behind the robot server. With a SteadyClock the robot then runs in real time;
// commands from other threads meanwhile are safe (the robot has its own lock). If the thread
// falls behind, the next update() integrates every period that is due, so the simulation
// never slips, it only gets coarser for a moment.

#include <condition_variable>
#include <mutex>
#include <thread>

#include "telear/sim/simulated_robot.hpp"

namespace telear::sim {

class ServoThread {
 public:
  // Starts the thread. `robot` must outlive this object; period > 0 (asserts).
  ServoThread(SimulatedRobot& robot, double period);
  ~ServoThread();  // stop()

  ServoThread(const ServoThread&) = delete;
  ServoThread& operator=(const ServoThread&) = delete;

  // Stops and joins the thread; idempotent.
  void stop();

 private:
  void run();

  SimulatedRobot& robot_;
  const double period_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace telear::sim
