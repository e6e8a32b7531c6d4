#pragma once
// One browser tab's operator: the session it drives (session::Session, the native console's),
// the console's view settings (console::UiState) and a thread of its own that runs them.
//
// The socket (web_server.hpp) hands every text message to receive(); the operator's thread
// takes them in order: `connect` starts a session with the typed token against the servers
// behind `telear web` -- a token the robot server refuses ends there, with its reason, before
// anything else is sent -- and `command` lines go through the console's own parser and
// apply_action(), so the page's buttons and command line are the console's action vocabulary,
// not a second one. The thread updates the session ~60 times a second and sends the state
// ~30 times a second; the video goes to the page from the vision client's receive thread, as
// the JPEGs arrived (latest wins in the socket's queue). A Session is used from this thread
// only (session.hpp); receive() and stop() may be called from any thread.

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "telear/console/ui_state.hpp"
#include "telear/core/arm_body.hpp"
#include "telear/core/robot_model.hpp"
#include "telear/render/scene_objects.hpp"
#include "telear/session/session.hpp"
#include "telear/web/operator_messages.hpp"

namespace telear::web {

// Where an operator's messages go: the socket's send queue (thread-safe). A replaceable
// message (the state, a video frame) that is still waiting when the next of its kind comes is
// dropped for it; the others (answers, the model) are all delivered, in order.
class OperatorOutbox {
 public:
  virtual ~OperatorOutbox() = default;
  enum class Kind { kOnce, kState, kVideo };
  virtual void send_text(std::string message, Kind kind = Kind::kOnce) = 0;
  virtual void send_binary(std::string message, Kind kind = Kind::kOnce) = 0;
};

// What every operator of one `telear web` shares, read-only once built.
struct OperatorSetup {
  core::RobotModelPtr model;
  core::ArmBody body;
  std::vector<render::SceneObject> objects;
  // Addresses, workspace, description, marker...; no token (each tab brings its own) and no
  // cameras when `cameras` is unset (then each session asks the vision server).
  session::SessionOptions session_options;
  std::optional<std::vector<EyeProjection>> eyes;  // the cameras at the video's size
  int width = 640, height = 480;                   // the video's size
  bool embedded = false;
  std::string model_json;  // model_message(body, objects), built once
};

class BrowserOperator {
 public:
  BrowserOperator(std::shared_ptr<const OperatorSetup> setup,
                  std::shared_ptr<OperatorOutbox> outbox);
  ~BrowserOperator();  // stop() and wait: the session ends (the lease released)
  BrowserOperator(const BrowserOperator&) = delete;
  BrowserOperator& operator=(const BrowserOperator&) = delete;

  void receive(std::string text);  // one text message from the page
  void stop();                     // returns at once; the thread ends its session

 private:
  void run();
  void handle(const std::string& text);
  void connect(const std::string& token);
  void command(std::int64_t id, const std::string& line);
  void send_state();
  std::string state_json();

  std::shared_ptr<const OperatorSetup> setup_;
  std::shared_ptr<OperatorOutbox> outbox_;
  std::unique_ptr<session::Session> session_;
  console::UiState ui_;
  std::string connection_;  // the last connection state sent
  double last_event_time_ = -1.0;
  std::optional<core::ArmBodyPose> ghost_pose_, real_pose_;
  // The plan's summary, recomputed when its waypoints change.
  std::string plan_key_;
  double plan_duration_s_ = 0.0;
  std::string plan_hash_;
  // Capture -> shown as the page measured it (ms), the last ~2 s.
  std::deque<std::pair<double, double>> shown_;

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::string> inbox_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace telear::web
