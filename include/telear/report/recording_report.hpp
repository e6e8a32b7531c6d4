#pragma once
// `telear report F.mcap -o DIR` as a library call: a recording read back
// (record::load_recording_series), its figures computed (recording_statistics.hpp), the plots
// drawn (recording_plots.hpp) and the Markdown summary written (recording_summary.hpp), all
// into DIR. The demo calls it on its own recording (lab/demo_workflow.hpp) with require_plots
// false, so a machine without gnuplot still gets its summary.

#include <string>
#include <vector>

#include "telear/core/result.hpp"
#include "telear/report/recording_plots.hpp"
#include "telear/report/recording_statistics.hpp"

namespace telear::report {

struct ReportOptions {
  std::string out_dir;                      // created when missing
  std::string markdown_name = "report.md";  // the summary's file name in out_dir
  PlotOptions plots;
  StatisticsOptions statistics;
  // true: a plot that cannot be drawn (no gnuplot) is an error and no summary is written;
  // false: the summary is written without plots and says why (ReportOutcome::plot_error).
  bool require_plots = true;

  // Errors name the field: out_dir empty, markdown_name not a plain file name.
  Status validate() const;
};

struct ReportOutcome {
  std::string markdown_path;
  std::vector<PlotFile> plots;  // empty when they could not be drawn
  std::string plot_error;       // why not (require_plots false)
  RecordingStatistics statistics;
  bool complete = true;  // the recording was closed (record::RecordingSeries::complete)
};

// Errors: the recording (missing, not MCAP, a message that does not decode: the reader's
// message naming the file), the output folder ("cannot create the output folder 'DIR': ...",
// "cannot write 'DIR/report.md': ..."), the plots (require_plots).
Result<ReportOutcome> write_recording_report(const std::string& mcap_path,
                                             const ReportOptions& options);

}  // namespace telear::report
