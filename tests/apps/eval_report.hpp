#pragma once
// `telear eval --json` reports as the CLI chain tests read them.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace telear::test {

// Reads the report at `path` and expects every one of its checks (17 or more) and the whole to
// pass, naming a failed check with its value and limit. Returns the report for the figures.
inline nlohmann::json expect_eval_report_passes(const std::string& path) {
  std::ifstream in(path);
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, false);
  EXPECT_FALSE(report.is_discarded()) << path << " is not JSON";
  if (report.is_discarded() || !report.contains("checks")) {
    ADD_FAILURE() << path << " has no checks";
    return nlohmann::json::object();
  }
  EXPECT_GE(report["checks"].size(), 17u);
  for (const auto& check : report["checks"]) {
    EXPECT_TRUE(check["pass"].get<bool>())
        << check["name"].get<std::string>() << " = " << check["value"].get<double>() << " (limit "
        << check["limit"].get<double>() << ")";
  }
  EXPECT_TRUE(report["pass"].get<bool>());
  return report;
}

}  // namespace telear::test
