#pragma once
// gnuplot as a child process fed through gnuplot-iostream (Debian's libgnuplot-iostream-dev):
// commands and inline data ('-' data sets, Gnuplot::send1d) go down one pipe to its standard
// input, so no data file is ever written; what it prints on standard error is collected and
// quoted when it fails. Internal to the report layer: the header pulls in Boost.Iostreams.
//
// gnuplot is started without a shell (posix_spawn: a path with spaces or quotes is just a
// path), its standard output sent to /dev/null. gnuplot reading a script from a pipe exits at
// its first error; a write after that would raise SIGPIPE, so SIGPIPE is blocked on the calling
// thread from start() to finish() (the write then fails with EPIPE, and a pending SIGPIPE is
// consumed before the mask is restored): the caller's process never dies of it.

#include <signal.h>
#include <sys/types.h>

#include <gnuplot-iostream.h>

#include <memory>
#include <string>
#include <thread>

#include "telear/core/result.hpp"

namespace telear::report {

// `program` as an executable path: a name (no '/') is looked up on PATH, a path is taken as it
// is. Error: "gnuplot not found (apt-get install gnuplot-nox)".
Result<std::string> find_gnuplot(const std::string& program = "gnuplot");

class GnuplotProcess {
 public:
  // Starts `executable` (an absolute path: find_gnuplot()). Errors: the spawn failed.
  static Result<std::unique_ptr<GnuplotProcess>> start(const std::string& executable);
  ~GnuplotProcess();  // finish()es if the caller did not
  GnuplotProcess(const GnuplotProcess&) = delete;
  GnuplotProcess& operator=(const GnuplotProcess&) = delete;

  // The stream to gnuplot's standard input (gnuplot-iostream: `gp() << "plot '-' ...\n";
  // gp().send1d(points);`). Valid until finish().
  gnuplotio::Gnuplot& gp() { return *gnuplot_; }

  // Closes gnuplot's input, waits for it to exit and restores the signal mask. Errors: gnuplot
  // exited with a failure or was killed (its standard error quoted), the pipe broke early.
  Status finish();

 private:
  GnuplotProcess() = default;

  std::string executable_;
  pid_t pid_ = -1;
  std::unique_ptr<gnuplotio::Gnuplot> gnuplot_;
  int stderr_fd_ = -1;
  std::string stderr_text_;
  std::thread stderr_reader_;
  sigset_t old_mask_{};
  bool finished_ = false;
};

}  // namespace telear::report
