#pragma once
// The servers a benchmark starts log every command and stream at info; a benchmark of thousands
// of calls keeps only warnings while it lives, and restores the level on the way out.

#include <spdlog/spdlog.h>

namespace telear::cli {

class QuietLog {
 public:
  QuietLog() : level_(spdlog::get_level()) { spdlog::set_level(spdlog::level::warn); }
  ~QuietLog() { spdlog::set_level(level_); }
  QuietLog(const QuietLog&) = delete;
  QuietLog& operator=(const QuietLog&) = delete;

 private:
  spdlog::level::level_enum level_;
};

}  // namespace telear::cli
