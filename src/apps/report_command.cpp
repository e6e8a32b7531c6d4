#include "apps/report_command.hpp"

#include <filesystem>

#include "apps/command_failure.hpp"
#include "telear/core/number_format.hpp"
#include "telear/record/mcap_reader.hpp"
#include "telear/report/recording_report.hpp"

namespace telear::cli {

int run_report(const ReportCommandOptions& options, std::ostream& out, std::ostream& err) {
  const CommandFailure fail{err, "telear report"};
  std::error_code error;
  // Said here in the command's words; the reader would say "McapReader: 'F': cannot open".
  // Bad input (exit 2, docs/cli.md): no file, or not a recording.
  if (!std::filesystem::exists(options.input, error)) {
    return fail("no such file: '" + options.input + "'");
  }
  if (auto reader = record::McapReader::open(options.input); !reader) {
    return fail(reader.error().message);
  }
  report::ReportOptions report;
  report.out_dir = options.output_dir;
  auto outcome = report::write_recording_report(options.input, report);
  if (!outcome) return fail(outcome.error().message, kExitFailure);
  out << "telear report: " << options.input << " ("
      << core::format_fixed(outcome->statistics.duration_s, 1) << " s"
      << (outcome->complete ? "" : ", not closed: read up to its last complete chunk") << ") -> "
      << outcome->markdown_path << "\n";
  for (const report::PlotFile& plot : outcome->plots) out << "  " << plot.path << "\n";
  return 0;
}

}  // namespace telear::cli
