#include "bench/kin_table.hpp"

#include <algorithm>

#include "telear/core/number_format.hpp"

namespace telear::bench {

std::string format_value(double v, const std::string& unit) {
  if (std::isnan(v)) return "-";
  if (unit == "%") return core::format_fixed(v, 2, "%");
  return core::format_fixed(v, v >= 1000.0 ? 0 : v >= 10.0 ? 1 : 2, unit);
}

std::string format_ratio(double r) {
  if (std::isnan(r)) return "-";
  return core::format_fixed(r, r >= 10.0 ? 0 : 1) + "x";
}

void print_table(const std::vector<Row>& rows, std::ostream& out) {
  const std::vector<std::string> header = {"operation",  "telear", "KDL",
                                           "KDL/telear", "target", "met"};
  std::vector<std::vector<std::string>> cells;
  for (const Row& r : rows) {
    cells.push_back({r.operation, format_value(r.telear, r.unit), format_value(r.kdl, r.unit),
                     format_ratio(r.ratio()), r.target, r.met});
  }
  std::vector<size_t> width(header.size());
  for (size_t c = 0; c < header.size(); ++c) {
    width[c] = header[c].size();
    for (const auto& line : cells) width[c] = std::max(width[c], line[c].size());
  }
  auto print_line = [&](const std::vector<std::string>& line) {
    std::string text;
    for (size_t c = 0; c < line.size(); ++c) {
      std::string cell = line[c];
      // Names and notes left-aligned, numbers right-aligned.
      const bool left = c == 0 || c + 1 >= line.size() - 1;
      const std::string pad(width[c] - cell.size(), ' ');
      text += left ? cell + pad : pad + cell;
      if (c + 1 < line.size()) text += " | ";
    }
    while (!text.empty() && text.back() == ' ') text.pop_back();
    out << text << "\n";
  };
  print_line(header);
  std::vector<std::string> rule;
  for (size_t w : width) rule.push_back(std::string(w, '-'));
  print_line(rule);
  for (const auto& line : cells) print_line(line);
}

std::string met_time(double value, double limit, const std::string& unit) {
  if (value <= limit) return "yes";
  return "no: " + format_value(value, unit) + " > " + format_value(limit, unit);
}

std::string met_ratio(double ratio, double wanted) {
  if (ratio >= wanted) return "yes";
  return "no: " + format_ratio(ratio) + " < " + format_ratio(wanted);
}

std::string join_met(const std::string& a, const std::string& b) {
  if (a == "yes" && b == "yes") return "yes";
  if (a == "yes") return b;
  if (b == "yes") return a;
  return a + "; " + b.substr(4);
}

}  // namespace telear::bench
