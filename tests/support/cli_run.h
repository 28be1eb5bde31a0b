// Running the built shadesim (or any command) from a test: exit status and all it printed.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace shadesim {

struct Result {
  int status = 0;
  std::string output;  // stdout and stderr
};

// `cmd` through the shell, stderr joined to stdout.
inline Result run_shell(const std::string& cmd) {
  Result r;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return {-1, "popen failed"};
  std::array<char, 4096> buf{};
  size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  const int raw = pclose(p);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

// The shadesim of this build with `args`.
inline Result run(const std::string& args) {
  return run_shell(std::string(SHADESIM_BINARY_DIR) + "/shadesim " + args);
}

// A fresh, empty folder of this test process.
inline std::filesystem::path temp_dir(const std::string& suite, const std::string& name) {
  auto d = std::filesystem::temp_directory_path() /
           ("shadesim_" + suite + "_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace shadesim
