#include "gnuplot_process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <ctime>

extern char** environ;

namespace telear::report {
namespace {

std::string errno_text(int error) {
  return std::strerror(error);
}

// What gnuplot printed, for an error message: its first few lines.
std::string first_lines(const std::string& text, int lines) {
  std::size_t end = 0;
  for (int i = 0; i < lines && end != std::string::npos; ++i) {
    end = text.find('\n', end == 0 ? 0 : end + 1);
  }
  std::string head = text.substr(0, end);
  while (!head.empty() && (head.front() == '\n' || head.front() == ' ')) head.erase(0, 1);
  for (char& c : head) {
    if (c == '\n') c = ' ';
  }
  return head;
}

}  // namespace

Result<std::unique_ptr<GnuplotProcess>> GnuplotProcess::start(const std::string& executable) {
  int input[2], errors[2];
  if (::pipe2(input, O_CLOEXEC) != 0) return Error{"gnuplot: pipe: " + errno_text(errno)};
  if (::pipe2(errors, O_CLOEXEC) != 0) {
    const int e = errno;
    ::close(input[0]);
    ::close(input[1]);
    return Error{"gnuplot: pipe: " + errno_text(e)};
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, input[0], STDIN_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, errors[1], STDERR_FILENO);
  std::string argv0 = executable;
  char* argv[] = {argv0.data(), nullptr};
  pid_t pid = -1;
  const int spawned = ::posix_spawn(&pid, executable.c_str(), &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(input[0]);
  ::close(errors[1]);
  if (spawned != 0) {
    ::close(input[1]);
    ::close(errors[0]);
    return Error{"cannot start gnuplot '" + executable + "': " + errno_text(spawned)};
  }

  std::unique_ptr<GnuplotProcess> p(new GnuplotProcess());
  p->executable_ = executable;
  p->pid_ = pid;
  p->stderr_fd_ = errors[0];
  // A thread drains its standard error as it comes: gnuplot must never block on a full pipe.
  p->stderr_reader_ = std::thread([fd = errors[0], text = &p->stderr_text_] {
    char buffer[4096];
    while (true) {
      const ssize_t n = ::read(fd, buffer, sizeof buffer);
      if (n > 0) {
        text->append(buffer, static_cast<std::size_t>(n));
      } else if (n == 0 || errno != EINTR) {
        return;
      }
    }
  });
  // After the spawn: the child must not inherit a blocked SIGPIPE.
  sigset_t pipe_signal;
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_signal, &p->old_mask_);
  FILE* stream = ::fdopen(input[1], "w");
  if (stream == nullptr) {
    const int e = errno;
    ::close(input[1]);
    Status ignored = p->finish();
    (void)ignored;
    return Error{"gnuplot: fdopen: " + errno_text(e)};
  }
  p->gnuplot_ = std::make_unique<gnuplotio::Gnuplot>(stream);  // fclose()s it when destroyed
  return p;
}

GnuplotProcess::~GnuplotProcess() {
  Status ignored = finish();
  (void)ignored;
}

Status GnuplotProcess::finish() {
  if (finished_) return Status::Ok();
  finished_ = true;
  bool write_failed = false;
  if (gnuplot_) {
    *gnuplot_ << std::flush;
    write_failed = !gnuplot_->good();
    gnuplot_.reset();  // closes gnuplot's input: it finishes the script and exits
  }
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  if (stderr_reader_.joinable()) stderr_reader_.join();
  ::close(stderr_fd_);
  // A write after gnuplot exited left a SIGPIPE pending on this thread: consume it, then
  // restore the caller's mask.
  sigset_t pipe_signal;
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  const timespec no_wait{0, 0};
  while (sigtimedwait(&pipe_signal, nullptr, &no_wait) == SIGPIPE) {
  }
  pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);

  const std::string said = first_lines(stderr_text_, 4);
  if (WIFSIGNALED(status)) {
    return Error{"gnuplot (" + executable_ + ") was killed by signal " +
                 std::to_string(WTERMSIG(status)) + (said.empty() ? "" : ": " + said)};
  }
  if (WEXITSTATUS(status) != 0 || write_failed) {
    return Error{"gnuplot (" + executable_ + ") failed" +
                 (WEXITSTATUS(status) != 0
                      ? " with exit status " + std::to_string(WEXITSTATUS(status))
                      : std::string(" (its input closed early)")) +
                 (said.empty() ? "" : ": " + said)};
  }
  return Status::Ok();
}

Result<std::string> find_gnuplot(const std::string& program) {
  const auto executable = [](const std::string& path) {
    struct stat info {};
    return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) &&
           ::access(path.c_str(), X_OK) == 0;
  };
  if (program.find('/') != std::string::npos) {
    if (executable(program)) return program;
    return Error{"gnuplot not found at '" + program + "' (apt-get install gnuplot-nox)"};
  }
  const char* path = std::getenv("PATH");
  const std::string dirs = path != nullptr ? path : "/usr/bin:/bin";
  std::size_t begin = 0;
  while (begin <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', begin), dirs.size());
    const std::string dir = end > begin ? dirs.substr(begin, end - begin) : ".";
    if (const std::string candidate = dir + "/" + program; executable(candidate)) {
      return candidate;
    }
    begin = end + 1;
  }
  return Error{program + " not found (apt-get install gnuplot-nox)"};
}

}  // namespace telear::report
