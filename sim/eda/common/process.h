// Running a child process without a shell (arguments are passed as they are, no quoting).
#pragma once

#include <string>
#include <vector>

namespace shadesim {

struct ProcessResult {
  int exit_code = -1;      // the child's exit status; 128 + signal when it was killed
  bool timed_out = false;  // killed because it ran past the timeout
  std::string output;      // stdout and stderr, when no log file was given
};

// Runs argv[0] with argv; stdout and stderr go to `log_path` (created/truncated), or are
// captured into ProcessResult::output when log_path is empty. Throws std::runtime_error when
// the program cannot be started.
ProcessResult run_process(const std::vector<std::string>& argv, const std::string& log_path);
// The same with a limit: past `timeout_seconds` (> 0) of wall time the child gets SIGTERM, and
// SIGKILL 5 s later if it is still there; the result says timed_out. 0: no limit.
ProcessResult run_process(const std::vector<std::string>& argv, const std::string& log_path,
                          double timeout_seconds);

// The full path of a program on PATH, or a std::runtime_error "<what>: '<name>' not found on PATH"
// naming the Debian package that provides it.
std::string find_program(const std::string& name, const std::string& package,
                         const std::string& what);

}  // namespace shadesim
