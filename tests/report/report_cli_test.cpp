// `telear report F.mcap -o DIR` as a user runs it: on a recording with a known tracking error
// (tests/record/synthetic_recording.hpp: the shoulder commanded 0.01 rad past its measurement,
// i.e. 0.573 deg), every plot is a PNG of its size with its data drawn in it, the summary
// has the figures, nothing else is left in DIR; and each error is one line naming the problem.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "record/synthetic_recording.hpp"
#include "telear/report/recording_plots.hpp"
#include "telear/vision/image_file.hpp"
#include "test_util/temp_dir.hpp"

namespace telear::report {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

// `environment` prefixes the command (e.g. "env PATH=/nowhere").
CliRun run_report(const std::string& arguments, const std::string& environment = "") {
  test_files::TempDir dir("report_cli_run");
  const std::string out = dir.file("stdout"), err = dir.file("stderr");
  const std::string command =
      environment + " " + TELEAR_BINARY + " report " + arguments + " > " + out + " 2> " + err;
  const int status = std::system(command.c_str());
  CliRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream o(out), e(err);
  std::stringstream so, se;
  so << o.rdbuf();
  se << e.rdbuf();
  r.out = so.str();
  r.err = se.str();
  return r;
}

// Pixels within `tolerance` of `colour` (RGB hex, as the plots set it) in a BGR image.
int pixels_of(const cv::Mat& image, unsigned rgb, int tolerance = 40) {
  const cv::Vec3b want((rgb >> 0) & 0xff, (rgb >> 8) & 0xff, (rgb >> 16) & 0xff);
  int n = 0;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const cv::Vec3b p = image.at<cv::Vec3b>(y, x);
      if (std::abs(p[0] - want[0]) + std::abs(p[1] - want[1]) + std::abs(p[2] - want[2]) <=
          tolerance)
        ++n;
    }
  }
  return n;
}

TEST(ReportCli, PlotsAndSummarizesARecordingWithAKnownTrackingError) {
  test_files::TempDir tmp("report_cli");
  const std::string mcap = tmp.file("session.mcap");
  test::SyntheticRecording r;
  r.command_offset[1] = 0.01;  // rad, on joint 2 (the PUMA's shoulder)
  ASSERT_TRUE(test::write_synthetic_recording(mcap, r));
  const std::string dir = tmp.file("plots");

  const CliRun run = run_report(mcap + " -o " + dir);
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_THAT(run.out, HasSubstr("-> " + dir + "/report.md"));
  EXPECT_EQ(run.err, "");

  // Every plot: a PNG of its size, with its data drawn in it (the series' colours), and
  // nothing else in the folder (the data went to gnuplot through its input, no files).
  struct Expected {
    std::string_view name;
    int height;
    unsigned colour;  // a colour the plot's data are drawn in
  };
  const Expected plots[] = {
      {kTrackingErrorPlot, kTrackingTitleHeightPx + 6 * kTrackingPanelHeightPx, 0x1f77b4},
      {kLatencyStagesPlot, kPlotHeightPx, 0x4e79a7},
      {kLatencyTotalPlot, kPlotHeightPx, 0x1f77b4},
      {kVideoRatePlot, kPlotHeightPx, 0xd62728},
      {kDisplayModePlot, kDisplayPlotHeightPx, 0x000000},  // no switches: the text says so
  };
  std::set<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    files.insert(entry.path().filename().string());
  }
  std::set<std::string> expected_files = {"report.md"};
  for (const Expected& p : plots) {
    const std::string path = dir + "/" + std::string(p.name);
    expected_files.insert(std::string(p.name));
    std::ifstream in(path, std::ios::binary);
    char magic[8] = {};
    in.read(magic, 8);
    EXPECT_EQ(std::string(magic, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << p.name;
    auto read = vision::read_image_file(path, vision::ImageFileMode::kColour);
    ASSERT_TRUE(read) << read.error().message;
    const cv::Mat image = *read;
    EXPECT_EQ(image.cols, kPlotWidthPx) << p.name;
    EXPECT_EQ(image.rows, p.height) << p.name;
    EXPECT_GT(pixels_of(image, p.colour), 50) << p.name;
    EXPECT_GT(image.cols * image.rows - pixels_of(image, 0xffffff, 0), 2000) << p.name;
  }
  EXPECT_EQ(files, expected_files);

  // The summary: the tracking error in degrees (0.01 rad = 0.573 deg on the shoulder, none
  // elsewhere), latency per stage, the cameras' rates, the topics, the events, the plots.
  std::ifstream in(dir + "/report.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string md = text.str();
  EXPECT_THAT(md, HasSubstr("# Recording session.mcap"));
  EXPECT_THAT(md, HasSubstr("| shoulder | deg | 0.573 | 0.573 |"));
  EXPECT_THAT(md, HasSubstr("| waist | deg | 0 | 0 |"));
  EXPECT_THAT(md, HasSubstr("50 states with their command"));
  EXPECT_THAT(md, HasSubstr("| network | 1.20 | 1.40 | 30 |"));
  EXPECT_THAT(md, HasSubstr("| total capture -> decoded | 10.20 | 10.40 | 30 |"));
  EXPECT_THAT(md, HasSubstr("| left | 30 | 30.00 | 0.031 | 0.03 |"));
  EXPECT_THAT(md, HasSubstr("| right | 30 | 30.00 | 0.047 | 0.04 |"));
  EXPECT_THAT(md, HasSubstr("| `/robot/joint_states` | 50 | 0 |"));
  EXPECT_THAT(md, HasSubstr("| items dropped by the recorder | 0 |"));
  EXPECT_THAT(md, HasSubstr("| robot | puma560 |"));
  EXPECT_THAT(md, HasSubstr("| warning | synthetic operator event |"));
  EXPECT_THAT(md, HasSubstr("No AR/VR switches recorded."));
  for (const Expected& p : plots) {
    EXPECT_THAT(md, HasSubstr("](" + std::string(p.name) + ")")) << p.name;
  }
}

TEST(ReportCli, ErrorsAreOneLineNamingTheProblem) {
  test_files::TempDir tmp("report_cli_errors");
  const std::string mcap = tmp.file("session.mcap");
  test::SyntheticRecording r;
  r.states = 5;
  r.frames = 2;
  ASSERT_TRUE(test::write_synthetic_recording(mcap, r));

  // The recording: missing, not MCAP (bad input: exit 2).
  const std::string missing = tmp.file("missing.mcap");
  CliRun run = run_report(missing + " -o " + tmp.file("a"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err, "telear report: no such file: '" + missing + "'\n");
  const std::string text = tmp.write("notes.mcap", "not a recording at all\n");
  run = run_report(text + " -o " + tmp.file("b"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err,
            "telear report: not an MCAP file: '" + text + "' does not start with the MCAP magic\n");
  EXPECT_FALSE(fs::exists(tmp.file("b")));

  // The folder: through a file, a file itself.
  run = run_report(mcap + " -o " + text + "/plots");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.err, HasSubstr("telear report: cannot create the output folder '" + text +
                                 "/plots': Not a directory"));
  run = run_report(mcap + " -o " + text);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.err, "telear report: the output folder '" + text + "' is a file\n");
  if (::geteuid() != 0) {  // root writes anywhere
    const std::string locked = tmp.file("locked");
    fs::create_directories(locked);
    fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    run = run_report(mcap + " -o " + locked);
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_EQ(run.err, "telear report: cannot write into the output folder '" + locked +
                           "': Permission denied\n");
    fs::permissions(locked, fs::perms::owner_all);
  }

  // gnuplot missing: said with the package to install; no summary without its plots.
  run = run_report(mcap + " -o " + tmp.file("c"), "env PATH=" + tmp.file("empty_path"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.err, "telear report: gnuplot not found (apt-get install gnuplot-nox)\n");
  EXPECT_FALSE(fs::exists(tmp.file("c/report.md")));

  // Usage: the file and -o are required (exit 2).
  run = run_report(mcap);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err, "telear report: --output is required\n");
  run = run_report("-o " + tmp.file("d"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err, "telear report: recording is required\n");
}

}  // namespace
}  // namespace telear::report
