// Running a child process without a shell (arguments are passed as they are, no quoting).
#pragma once

#include <string>
#include <vector>

namespace shadesim {

struct ProcessResult {
  int exit_code = -1;  // the child's exit status; 128 + signal when it was killed
  std::string output;  // stdout and stderr, when no log file was given
};

// Runs argv[0] with argv; stdout and stderr go to `log_path` (created/truncated), or are
// captured into ProcessResult::output when log_path is empty. Throws std::runtime_error when
// the program cannot be started.
ProcessResult run_process(const std::vector<std::string>& argv, const std::string& log_path);

}  // namespace shadesim
