#pragma once
// The Markdown summary of a recording (`telear report`'s report.md): what the file holds and
// the figures behind each plot, README-like, with the plots embedded beside their tables.
//
//   the file     duration, robot and who recorded it (telear.session metadata), whether it was
//                closed (a killed recorder's file is read up to its last complete chunk)
//   topics       messages per topic, and items the recorder dropped (telear.recording)
//   tracking     RMS and max |commanded - measured| per joint, in the joint's unit
//   latency      median and p95 per stage (ms)
//   video        frames, mean fps and MB/s of JPEG per camera
//   display      the AR/VR switches
//   events       /events in time order (the first kMaxSummaryEvents)

#include <cstddef>
#include <string>
#include <vector>

#include "telear/record/recording_series.hpp"
#include "telear/report/recording_plots.hpp"
#include "telear/report/recording_statistics.hpp"

namespace telear::report {

inline constexpr std::size_t kMaxSummaryEvents = 200;

// `plots` are embedded by file name (the Markdown sits beside them); `plot_note`, when not
// empty, says why there are none ("plots not drawn: gnuplot not found ...").
std::string recording_summary_markdown(const record::RecordingSeries& series,
                                       const RecordingStatistics& statistics,
                                       const std::vector<PlotFile>& plots,
                                       const std::string& plot_note = "");

}  // namespace telear::report
