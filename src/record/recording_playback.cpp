#include "telear/record/recording_playback.hpp"

#include <algorithm>

#include "foxglove/CompressedImage.pb.h"
#include "telear/net/jpeg_codec.hpp"
#include "telear/record/mcap_reader.hpp"
#include "telear/record/recording_topics.hpp"
#include "telear/vision/camera_file.hpp"

namespace telear::record {

struct RecordingPlayback::State {
  RecordingSeries series;
  vision::StereoCameraModel cameras;
  std::string workspace_yaml;
  McapReader reader;
  net::JpegDecoder decoder;
  std::optional<PlaybackFrame> last;

  State(RecordingSeries s, McapReader r) : series(std::move(s)), reader(std::move(r)) {}

  // The JPEG of `topic` logged at exactly `log_ns` (both eyes of a pair share their log time).
  Result<core::Image> decode(std::string_view topic, std::uint64_t log_ns) {
    McapReadOptions options;
    options.start_ns = options.end_ns = log_ns;
    options.topics = {std::string(topic)};
    std::optional<Result<core::Image>> image;
    Status read = reader.read_messages(
        [&](const McapMessageView& m) {
          foxglove::CompressedImage message;
          if (!message.ParseFromArray(m.data.data(), static_cast<int>(m.data.size()))) {
            image = Error{std::string(topic) + ": a message that is not a CompressedImage"};
          } else {
            image = decoder.decode(message.data());
          }
          return false;
        },
        options);
    if (!read) return read.error();
    if (!image) return Error{std::string(topic) + ": no frame at that time"};
    if (!*image) return Error{std::string(topic) + ": " + image->error().message};
    return std::move(*image);
  }
};

RecordingPlayback::RecordingPlayback(std::unique_ptr<State> state) : state_(std::move(state)) {}
RecordingPlayback::RecordingPlayback(RecordingPlayback&&) noexcept = default;
RecordingPlayback& RecordingPlayback::operator=(RecordingPlayback&&) noexcept = default;
RecordingPlayback::~RecordingPlayback() = default;

Result<RecordingPlayback> RecordingPlayback::open(const std::string& path) {
  auto series = load_recording_series(path);
  if (!series) return series.error();
  if (series->calibration_yaml.empty()) {
    return Error{"'" + path + "' records no calibration: nothing to draw the arm through"};
  }
  auto file = vision::parse_camera_yaml(series->calibration_yaml, path + " (calibration.yaml)");
  if (!file) return file.error();
  if (!file->right) return Error{"'" + path + "': its calibration.yaml is not a stereo pair"};
  auto reader = McapReader::open(path);
  if (!reader) return reader.error();
  auto state = std::make_unique<State>(std::move(*series), std::move(*reader));
  state->cameras = {file->left, *file->right};
  auto attachments = state->reader.attachments();
  if (!attachments) return attachments.error();
  for (const McapAttachment& a : *attachments) {
    if (a.name == "workspace.yaml") state->workspace_yaml.assign(a.data.begin(), a.data.end());
  }
  return RecordingPlayback(std::move(state));
}

const RecordingSeries& RecordingPlayback::series() const {
  return state_->series;
}
const vision::StereoCameraModel& RecordingPlayback::cameras() const {
  return state_->cameras;
}
const std::string& RecordingPlayback::workspace_yaml() const {
  return state_->workspace_yaml;
}

std::string RecordingPlayback::robot_spec() const {
  const auto session = state_->series.metadata.find("telear.session");
  if (session == state_->series.metadata.end()) return {};
  for (const char* key : {"robot_spec", "robot"}) {
    const auto it = session->second.find(key);
    if (it != session->second.end() && !it->second.empty()) return it->second;
  }
  return {};
}

std::string RecordingPlayback::robot_tip() const {
  const auto session = state_->series.metadata.find("telear.session");
  if (session == state_->series.metadata.end()) return {};
  const auto it = session->second.find("robot_tip");
  return it == session->second.end() ? std::string() : it->second;
}

std::int64_t RecordingPlayback::pair_stamp(std::size_t index) const {
  const RecordingSeries& s = state_->series;
  std::int64_t stamp = s.frames[0][index].stamp_ns;
  if (index < s.frames[1].size() && s.frames[1][index].log_ns == s.frames[0][index].log_ns) {
    stamp = std::max(stamp, s.frames[1][index].stamp_ns);
  }
  return stamp;
}

PlaybackMoment RecordingPlayback::at(double t) const {
  const RecordingSeries& s = state_->series;
  PlaybackMoment moment;
  moment.t = std::clamp(t, 0.0, s.duration_s());
  moment.log_ns = s.start_ns + static_cast<std::uint64_t>(moment.t * 1e9 + 0.5);
  if (moment.t >= s.duration_s()) moment.log_ns = s.end_ns;
  const auto& left = s.frames[0];
  const auto after =
      std::upper_bound(left.begin(), left.end(), moment.log_ns,
                       [](std::uint64_t ns, const FrameSample& f) { return ns < f.log_ns; });
  if (after != left.begin()) moment.frame = static_cast<std::size_t>(after - left.begin()) - 1;
  // The newest decoded pair: back from the newest received to the one the latency names.
  const auto decoded =
      std::upper_bound(s.latency.begin(), s.latency.end(), moment.log_ns,
                       [](std::uint64_t ns, const LatencySample& l) { return ns < l.log_ns; });
  if (moment.frame && decoded != s.latency.begin()) {
    const std::int64_t shown = std::prev(decoded)->stamp_ns;
    for (std::size_t i = *moment.frame + 1; i-- > 0;) {
      if (pair_stamp(i) == shown) {
        moment.frame = i;
        break;
      }
      if (pair_stamp(i) < shown) break;  // not recorded: keep the newest received
    }
  }
  moment.ghost = s.ghost.at(moment.log_ns);
  moment.robot = s.robot.at(moment.log_ns);
  // The mode: the last switch's; before the first switch, the mode it switched from (a
  // session's view starts in VR, so its first switch is to AR); no switch recorded: AR.
  bool first = true;
  for (const PlanEventSample& e : s.plan_events) {
    if (e.kind_name != "DISPLAY_MODE") continue;
    const bool to_vr = e.text.rfind("vr", 0) == 0;
    if (e.t > moment.t) {
      if (first) moment.vr = !to_vr;
      break;
    }
    moment.vr = to_vr;
    first = false;
  }
  if (moment.frame) {
    moment.frame_age_s = static_cast<double>(static_cast<std::int64_t>(moment.log_ns) -
                                             left[*moment.frame].stamp_ns) *
                         1e-9;
  }
  return moment;
}

Result<const PlaybackFrame*> RecordingPlayback::frame(std::size_t index) {
  State& s = *state_;
  const auto& left = s.series.frames[0];
  if (index >= left.size()) {
    return Error{"frame " + std::to_string(index) + ": the recording has " +
                 std::to_string(left.size())};
  }
  if (s.last && s.last->index == index) return &*s.last;
  PlaybackFrame frame;
  frame.index = index;
  frame.log_ns = left[index].log_ns;
  frame.stamp_ns = left[index].stamp_ns;
  auto l = s.decode(kTopicLeftImage, frame.log_ns);
  if (!l) return l.error();
  auto r = s.decode(kTopicRightImage, frame.log_ns);
  if (!r) return r.error();
  frame.left = std::move(*l);
  frame.right = std::move(*r);
  s.last = std::move(frame);
  return &*s.last;
}

}  // namespace telear::record
