#include "telear/report/recording_report.hpp"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "telear/record/recording_series.hpp"
#include "telear/report/recording_summary.hpp"

namespace telear::report {

namespace fs = std::filesystem;

Status ReportOptions::validate() const {
  if (out_dir.empty()) return Error{"report: the output folder is not given"};
  if (markdown_name.empty() || markdown_name.find('/') != std::string::npos ||
      markdown_name == "." || markdown_name == "..") {
    return Error{"report: the summary's name '" + markdown_name + "' is not a plain file name"};
  }
  if (!(statistics.window_s > 0.0) || !std::isfinite(statistics.window_s)) {
    return Error{"report: the video rate's window must be > 0 s"};
  }
  if (statistics.latency_windows < 1) {
    return Error{"report: the latency windows must be 1 or more, got " +
                 std::to_string(statistics.latency_windows)};
  }
  return Status::Ok();
}

Result<ReportOutcome> write_recording_report(const std::string& mcap_path,
                                             const ReportOptions& options) {
  if (Status s = options.validate(); !s) return s.error();
  auto series = record::load_recording_series(mcap_path);
  if (!series) return series.error();

  // The folder, before gnuplot is started: a path through a file, or a folder this process may
  // not write into, is said as such rather than as gnuplot's "cannot open file".
  const std::string& dir = options.out_dir;
  std::error_code error;
  if (fs::exists(dir, error) && !fs::is_directory(dir, error)) {
    return Error{"the output folder '" + dir + "' is a file"};
  }
  fs::create_directories(dir, error);
  if (error) return Error{"cannot create the output folder '" + dir + "': " + error.message()};
  if (::access(dir.c_str(), W_OK | X_OK) != 0) {
    return Error{"cannot write into the output folder '" + dir + "': " + std::strerror(errno)};
  }

  ReportOutcome outcome;
  outcome.complete = series->complete;
  outcome.statistics = recording_statistics(*series, options.statistics);
  auto plots = write_recording_plots(outcome.statistics, dir, options.plots);
  if (plots) {
    outcome.plots = std::move(plots).value();
  } else if (options.require_plots) {
    return plots.error();
  } else {
    outcome.plot_error = plots.error().message;
  }
  const std::string note =
      outcome.plot_error.empty() ? std::string() : "Plots not drawn: " + outcome.plot_error + ".";
  const std::string markdown =
      recording_summary_markdown(*series, outcome.statistics, outcome.plots, note);
  outcome.markdown_path = (fs::path(dir) / options.markdown_name).string();
  std::ofstream out(outcome.markdown_path, std::ios::binary | std::ios::trunc);
  out << markdown;
  out.close();
  if (!out) {
    return Error{"cannot write '" + outcome.markdown_path + "': " + std::strerror(errno)};
  }
  return outcome;
}

}  // namespace telear::report
