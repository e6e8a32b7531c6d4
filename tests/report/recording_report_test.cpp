// The report's figures, plots and summary as a library call (report::write_recording_report),
// on recordings whose content is known: the synthetic session of tests/record (a command 0.01 rad
// off the measurement on one joint, latencies and frame rates by construction) and a file of
// AR/VR switches written event by event.

#include "telear/report/recording_report.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "record/synthetic_recording.hpp"
#include "telear/record/mcap_writer.hpp"
#include "telear/record/recording_topics.hpp"
#include "telear/record/schema_descriptors.hpp"
#include "telear/record/v1/plan_event.pb.h"
#include "telear/report/recording_summary.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::report {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(RecordingStatistics, TrackingLatencyAndVideoFiguresFromASyntheticSession) {
  test_files::TempDir tmp("report_statistics");
  const std::string path = tmp.file("synthetic.mcap");
  test::SyntheticRecording r;
  r.command_offset[1] = 0.01;  // shoulder: commanded 0.01 rad past the measurement
  ASSERT_TRUE(test::write_synthetic_recording(path, r));
  auto series = record::load_recording_series(path);
  ASSERT_TRUE(series) << series.error().message;
  const RecordingStatistics s = recording_statistics(*series);

  // Every state paired with its command; the PUMA's joints are revolute: degrees.
  EXPECT_EQ(s.tracking_samples, static_cast<std::size_t>(r.states));
  ASSERT_EQ(s.tracking.size(), 6u);
  const double offset_deg = 0.01 * 180.0 / std::numbers::pi;  // 0.5730
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(s.tracking[i].unit.name, "deg");
    EXPECT_EQ(s.tracking[i].error.size(), static_cast<std::size_t>(r.states));
    EXPECT_NEAR(s.tracking[i].rms, i == 1 ? offset_deg : 0.0, 1e-9) << i;
    EXPECT_NEAR(s.tracking[i].max_abs, i == 1 ? offset_deg : 0.0, 1e-9) << i;
  }
  EXPECT_EQ(s.tracking[1].joint, "shoulder");

  // Latency: the network stage cycles 1.0 .. 1.4 ms over the 30 frames (six each): nearest-rank
  // median 1.2 ms (the 15th of 30), p95 1.4 ms; the total is 9 ms of constant stages plus it.
  const StageFigures& network = s.latency.stages[3];
  EXPECT_EQ(network.samples, 30u);
  EXPECT_NEAR(network.median_s, 0.0012, 1e-12);
  EXPECT_NEAR(network.p95_s, 0.0014, 1e-12);
  EXPECT_NEAR(s.latency.stages[net::kTotalLatencyStage].median_s, 0.0102, 1e-12);
  EXPECT_NEAR(s.latency.stages[0].median_s, 0.004, 1e-12);
  EXPECT_EQ(s.latency.total_s.size(), 30u);
  ASSERT_FALSE(s.latency.windows.empty());
  std::size_t windowed = 0;
  for (const LatencyWindow& w : s.latency.windows) windowed += w.samples;
  EXPECT_EQ(windowed, 30u);  // each frame in exactly one window

  // Video: 30 frames 33.33 ms apart: 30 fps; 1000 and 1500 bytes per frame.
  for (const CameraRate& c : s.cameras) EXPECT_EQ(c.frames, 30u);
  EXPECT_NEAR(s.cameras[0].fps_mean, 30.0, 1e-6);
  EXPECT_NEAR(s.cameras[0].mb_per_s_mean, 30 * 1000 / (29 * 0.033333333) / 1e6, 1e-6);
  EXPECT_NEAR(s.cameras[1].mb_per_s_mean, 30 * 1500 / (29 * 0.033333333) / 1e6, 1e-6);
  ASSERT_FALSE(s.cameras[0].fps.empty());
  EXPECT_NEAR(s.cameras[0].fps.front(), 30.0, 1.01);  // 30 or 31 frames in the first second

  EXPECT_TRUE(s.display.empty());
  ASSERT_TRUE(s.dropped_total.has_value());
  EXPECT_EQ(*s.dropped_total, 0u);
}

TEST(RecordingStatistics, JointUnitsFollowTheUrdfJointTypes) {
  record::RecordingSeries series;
  series.urdf = read_text(std::string(TELEAR_TEST_FILES_DIR) + "/urdf/prismatic.urdf");
  const auto units = joint_units(series, {"turn", "slide", "tilt", "nosuch"});
  ASSERT_EQ(units.size(), 4u);
  EXPECT_EQ(units[0].name, "deg");
  EXPECT_NEAR(units[0].per_si, 180.0 / std::numbers::pi, 1e-12);
  EXPECT_EQ(units[1].name, "mm");
  EXPECT_DOUBLE_EQ(units[1].per_si, 1000.0);
  EXPECT_EQ(units[2].name, "deg");
  EXPECT_EQ(units[3].name, "rad");  // not in the URDF: radians, labelled so
  series.urdf.clear();
  for (const JointUnit& u : joint_units(series, {"turn", "slide"})) EXPECT_EQ(u.name, "rad");
}

// A file with DISPLAY_MODE plan events only (as the console and the demo write them) and
// nothing else: the switches are read, and every other plot says what is missing.
TEST(RecordingReport, AvrSwitchesArePlottedAndListedAndMissingDataIsSaid) {
  test_files::TempDir tmp("report_display");
  const std::string path = tmp.file("switches.mcap");
  {
    auto writer = record::McapWriter::open(path);
    ASSERT_TRUE(writer) << writer.error().message;
    const record::SchemaInfo schema = record::schema_for<telear::record::v1::PlanEvent>();
    const std::uint16_t channel = writer->add_channel(
        writer->add_schema(schema.name, schema.encoding, record::mcap_bytes(schema.data)),
        record::kTopicPlanEvents, record::kProtobufEncoding);
    const std::uint64_t base = 1'700'000'000'000'000'000;
    struct Event {
      double t;
      telear::record::v1::PlanEvent::Kind kind;
      const char* text;
    };
    const Event events[] = {
        {0.0, telear::record::v1::PlanEvent::DISPLAY_MODE, "ar: video fresh"},
        {1.5, telear::record::v1::PlanEvent::DISPLAY_MODE, "vr: video 420 ms late"},
        {2.0, telear::record::v1::PlanEvent::EXECUTE, "vr is not a display event here"},
        {2.5, telear::record::v1::PlanEvent::DISPLAY_MODE, "automatic"},  // neither: ignored
        {3.25, telear::record::v1::PlanEvent::DISPLAY_MODE, "ar: 5 fresh frames"},
        {4.0, telear::record::v1::PlanEvent::ESTOP, "e-stop"},
    };
    std::uint32_t sequence = 0;
    for (const Event& e : events) {
      telear::record::v1::PlanEvent message;
      message.set_kind(e.kind);
      message.set_text(e.text);
      const auto t = base + static_cast<std::uint64_t>(e.t * 1e9);
      ASSERT_TRUE(writer->write(channel, ++sequence, t, t,
                                record::mcap_bytes(message.SerializeAsString())));
    }
    ASSERT_TRUE(writer->close());
  }
  ReportOptions options;
  options.out_dir = tmp.file("out");
  auto outcome = write_recording_report(path, options);
  ASSERT_TRUE(outcome) << outcome.error().message;
  const RecordingStatistics& s = outcome->statistics;
  ASSERT_EQ(s.display.size(), 3u);
  EXPECT_EQ(s.display[0].mode, DisplayMode::kAr);
  EXPECT_EQ(s.display[1].mode, DisplayMode::kVr);
  EXPECT_DOUBLE_EQ(s.display[1].t, 1.5);
  EXPECT_EQ(s.display[2].mode, DisplayMode::kAr);
  EXPECT_DOUBLE_EQ(s.display[2].t, 3.25);
  EXPECT_DOUBLE_EQ(s.duration_s, 4.0);
  ASSERT_EQ(outcome->plots.size(), 5u);
  for (const PlotFile& p : outcome->plots) EXPECT_TRUE(std::filesystem::exists(p.path)) << p.path;

  const std::string md = read_text(outcome->markdown_path);
  EXPECT_EQ(outcome->markdown_path, options.out_dir + "/report.md");
  EXPECT_THAT(md, HasSubstr("Switches to VR: 1, to AR: 2 "));
  EXPECT_THAT(md, HasSubstr("- t = 1.50 s: VR (vr: video 420 ms late)"));
  EXPECT_THAT(md, HasSubstr("No joint commands recorded."));
  EXPECT_THAT(md, HasSubstr("No latency recorded"));
  EXPECT_THAT(md, HasSubstr("| items dropped by the recorder | unknown"));
  EXPECT_THAT(md, HasSubstr("![AR / VR display mode against time](display_mode.png)"));
}

// The demo's use: without gnuplot the summary is still written, and says why it has no plots.
TEST(RecordingReport, WithoutGnuplotTheSummarySaysWhyThereAreNoPlots) {
  test_files::TempDir tmp("report_no_gnuplot");
  const std::string path = tmp.file("synthetic.mcap");
  test::SyntheticRecording r;
  r.states = 10;
  r.frames = 5;
  ASSERT_TRUE(test::write_synthetic_recording(path, r));
  ReportOptions options;
  options.out_dir = tmp.file("out");
  options.markdown_name = "recording_report.md";
  options.plots.gnuplot = tmp.file("no/gnuplot");
  options.require_plots = false;
  auto outcome = write_recording_report(path, options);
  ASSERT_TRUE(outcome) << outcome.error().message;
  EXPECT_TRUE(outcome->plots.empty());
  EXPECT_THAT(outcome->plot_error, HasSubstr("gnuplot not found at '" + options.plots.gnuplot));
  const std::string md = read_text(options.out_dir + "/recording_report.md");
  EXPECT_THAT(md, HasSubstr("Plots not drawn: gnuplot not found at"));
  EXPECT_THAT(md, Not(HasSubstr(".png")));
  // Required (telear report's way): an error, and no summary.
  options.require_plots = true;
  options.out_dir = tmp.file("out2");
  auto required = write_recording_report(path, options);
  ASSERT_FALSE(required);
  EXPECT_THAT(required.error().message, HasSubstr("(apt-get install gnuplot-nox)"));
  EXPECT_FALSE(std::filesystem::exists(options.out_dir + "/recording_report.md"));
  // Options that cannot work are refused naming the field.
  options.markdown_name = "sub/report.md";
  EXPECT_THAT(write_recording_report(path, options).error().message,
              HasSubstr("the summary's name 'sub/report.md' is not a plain file name"));
}

}  // namespace
}  // namespace telear::report
