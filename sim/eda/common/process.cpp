#include "sim/eda/common/process.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "model/text_file.h"

extern char** environ;

namespace shadesim {

std::string find_program(const std::string& name, const std::string& package,
                         const std::string& what) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::filesystem::path p = std::filesystem::path(dir.empty() ? "." : dir) / name;
    if (access(p.c_str(), X_OK) == 0) return p.string();
  }
  throw std::runtime_error(what + ": '" + name + "' not found on PATH (Debian package " + package +
                           "; scripts/setup installs it)");
}

ProcessResult run_process(const std::vector<std::string>& argv, const std::string& log_path) {
  return run_process(argv, log_path, 0.0);
}

namespace {

// Waits for `pid`; with a timeout, polls and kills it (TERM, then KILL) once it has run too long.
int wait_child(pid_t pid, double timeout_seconds, bool& timed_out) {
  int status = 0;
  if (timeout_seconds <= 0) {
    while (waitpid(pid, &status, 0) < 0) {
      if (errno != EINTR) throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
    }
    return status;
  }
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto term_sent = clock::time_point{};
  for (;;) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) return status;
    if (r < 0 && errno != EINTR)
      throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
    const double elapsed = std::chrono::duration<double>(clock::now() - start).count();
    if (!timed_out && elapsed > timeout_seconds) {
      timed_out = true;
      kill(pid, SIGTERM);
      term_sent = clock::now();
    } else if (timed_out && clock::now() - term_sent > std::chrono::seconds(5)) {
      kill(pid, SIGKILL);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace

ProcessResult run_process(const std::vector<std::string>& argv, const std::string& log_path,
                          double timeout_seconds) {
  if (argv.empty()) throw std::invalid_argument("run_process: no program");
  // Without a log file, capture through a temporary file (simple, no pipe deadlocks).
  std::string path = log_path;
  if (path.empty()) {
    char tmpl[] = "/tmp/shadesim_out_XXXXXX";
    const int fd = mkstemp(tmpl);
    if (fd < 0)
      throw std::runtime_error(std::string("run_process: mkstemp: ") + std::strerror(errno));
    close(fd);
    path = tmpl;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  std::vector<char*> args;
  args.reserve(argv.size() + 1);
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    throw std::runtime_error("cannot run '" + argv[0] + "': " + std::strerror(rc));
  }
  ProcessResult r;
  const int status = wait_child(pid, timeout_seconds, r.timed_out);
  r.exit_code =
      WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  if (log_path.empty()) {
    r.output = read_text_file(path);
    std::remove(path.c_str());
  }
  return r;
}

}  // namespace shadesim
