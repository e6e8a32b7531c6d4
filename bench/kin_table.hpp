#pragma once
// The table `telear bench kin` prints: one row per operation, telear's figure beside KDL's,
// their ratio, the target and whether it is met ("yes" or "no: why"). Numbers are
// fixed-point with their unit (core::format_fixed); cells are padded into aligned columns.

#include <cmath>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

namespace telear::bench {

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();  // no figure

struct Row {
  std::string operation;
  std::string unit;  // "ns", "us" or "%"
  double telear = kNone;
  double kdl = kNone;  // kNone: KDL has no counterpart
  std::string target;
  std::string met;  // "", "yes" or "no: why"
  // KDL / telear: how many times faster telear is (time rows with a KDL figure).
  double ratio() const { return unit == "%" || std::isnan(kdl) ? kNone : kdl / telear; }
};

// "812 ns", "12.5 us", "99.95 %"; "-" for kNone.
std::string format_value(double v, const std::string& unit);
// "3.2x", "15x"; "-" for kNone.
std::string format_ratio(double r);
void print_table(const std::vector<Row>& rows, std::ostream& out);

// "yes" or "no: 12.5 us > 10.0 us".
std::string met_time(double value, double limit, const std::string& unit);
// "yes" or "no: 3.2x < 10x".
std::string met_ratio(double ratio, double wanted);
// Both verdicts in one cell: "yes" when both are met, else the reasons joined by "; ".
std::string join_met(const std::string& a, const std::string& b);

}  // namespace telear::bench
