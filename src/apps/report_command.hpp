#pragma once
// `telear report F.mcap -o DIR`: plots (PNG, drawn by gnuplot) and a Markdown summary of a
// recording (report::write_recording_report; docs/recording.md, "Plots: telear report").

#include <ostream>
#include <string>

namespace telear::cli {

struct ReportCommandOptions {
  std::string input;       // the .mcap file
  std::string output_dir;  // -o DIR
};

// Exit 0 when every plot and the summary are written; 1 when the recording cannot be read, the
// folder cannot be written or gnuplot fails (one line "telear report: ..." on `err`).
int run_report(const ReportCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace telear::cli
