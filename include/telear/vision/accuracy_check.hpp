#pragma once
// The verdict of a calibration + registration against ground truth (docs/registration.md,
// "Accuracy against ground truth"; issue 4 item 7): the targets, one check per figure, and
// the JSON report `telear eval --json` writes and the demo's report embeds.
//
// Checks, in order, per eye (left, then right): |fx error| and |fy error| in % of the true
// focal length, |cx error| and |cy error| in px, registration position error in mm and
// rotation error in deg (include/telear/vision/overlay_accuracy.hpp), overlay RMS and max in
// px; then the |baseline error| in mm. A check passes when its value is finite and <= limit.

#include <string>
#include <vector>

#include "telear/vision/overlay_accuracy.hpp"

namespace telear::vision {

// Issue 4 item 7.
struct AccuracyTargets {
  double focal_percent = 0.2;
  double principal_point_px = 1.0;
  double baseline_mm = 0.5;
  double registration_mm = 1.0;
  double registration_deg = 0.1;
  double overlay_rms_px = 0.5;
  double overlay_max_px = 1.5;
};

struct AccuracyCheck {
  std::string name;  // e.g. "left fx error %"
  double value = 0.0;
  double limit = 0.0;
  bool pass() const;
};

std::vector<AccuracyCheck> accuracy_checks(const AccuracyReport& report,
                                           const AccuracyTargets& targets = {});
bool all_pass(const std::vector<AccuracyCheck>& checks);

// The report as JSON text (2-space indent, trailing newline): per eye "truth" and "estimate"
// intrinsics, fx/fy_error_percent, cx/cy_error_px, registration_mm, registration_deg,
// overlay_rms_px, overlay_max_px, overlay_points; then baseline_truth_mm,
// baseline_estimate_mm, overlay_configurations, overlay_samples_per_configuration, "checks"
// (name, value, limit, pass) and "pass" (all of them).
std::string accuracy_report_json(const AccuracyReport& report,
                                 const std::vector<AccuracyCheck>& checks);

// The table `telear eval` prints: per eye the intrinsics (truth, estimate, error), the
// registration and overlay errors; the baseline; the overlay's sample counts; then every
// check against its target, PASS or FAIL, and the overall verdict.
std::string accuracy_report_text(const AccuracyReport& report,
                                 const std::vector<AccuracyCheck>& checks);

}  // namespace telear::vision
