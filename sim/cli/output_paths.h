// Output paths checked before any work starts (issue 23): every option that names a file or a
// folder shadesim will write (-o/--out, --json, --junit, --save-stream, --plot, --waves, ...)
// is tried when the command line is parsed, so `-o /proc/x` or `--json /unwritable/f` fails at
// once, naming the option and the path, instead of with a raw filesystem error or after the
// whole run. The one home of the rule: commands attach output_file() / output_folder() to their
// options, or call check_output_path() on a path they forward.
#pragma once

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace shadesim {

// Why `path` cannot be written as a file (folder = false) or as a folder to write into
// (folder = true); "" when it can. Tries it for real: creates the missing folders, opens the file
// for appending (or creates and deletes a probe file in the folder), then removes whatever it
// created, so an existing file is left unchanged and a new path leaves nothing behind.
inline std::string output_path_problem_once(const std::string& path, bool folder) {
  namespace fs = std::filesystem;
  if (path.empty()) return "an empty path";
  std::error_code ec;
  fs::path target = fs::absolute(fs::path(path), ec).lexically_normal();
  if (ec) return "cannot resolve " + path + ": " + ec.message();
  if (!target.has_filename() && target.has_parent_path()) target = target.parent_path();
  // The folders that do not exist yet, deepest first, and the nearest one that does.
  std::vector<fs::path> missing;
  fs::path existing = folder ? target : target.parent_path();
  while (!fs::exists(existing, ec) && existing.has_relative_path()) {
    missing.push_back(existing);
    existing = existing.parent_path();
  }
  if (!fs::is_directory(existing, ec)) return existing.string() + " is not a folder";
  if (fs::exists(target, ec) && fs::is_directory(target, ec) != folder) {
    return path + (folder ? " is a file, not a folder" : " is a folder, not a file");
  }
  auto clean_up = [&] {
    for (const fs::path& d : missing) fs::remove(d, ec);  // deepest first; only if empty
  };
  if (!missing.empty()) {
    fs::create_directories(missing.front(), ec);
    if (ec) {
      const std::string why = ec.message();
      clean_up();
      return "cannot create the folder " + missing.back().string() + ": " + why;
    }
  }
  const fs::path file =
      folder ? target / (".shadesim-write-check-" + std::to_string(getpid())) : target;
  const bool existed = fs::exists(file, ec);
  std::FILE* f = std::fopen(file.c_str(), "a");
  if (f == nullptr) {
    const std::string why = std::strerror(errno);
    clean_up();
    return "cannot write " + (folder ? "into the folder " + target.string() : target.string()) +
           ": " + why;
  }
  std::fclose(f);
  if (!existed) fs::remove(file, ec);
  clean_up();
  return "";
}

// output_path_problem_once, looked at again when it fails: two runs checking the same new folder
// at once (ctest -j) see it created and removed by each other's probe, which is no problem of
// the path. A real problem is there every time.
inline std::string output_path_problem(const std::string& path, bool folder) {
  std::string problem = output_path_problem_once(path, folder);
  for (int again = 0; again < 5 && !problem.empty(); ++again) {
    usleep(2000 * (again + 1));
    problem = output_path_problem_once(path, folder);
  }
  return problem;
}

// Throws std::invalid_argument "OPTION: cannot write ..." when `path` cannot be written.
inline void check_output_path(const std::string& path, bool folder, const std::string& option) {
  const std::string problem = output_path_problem(path, folder);
  if (!problem.empty()) throw std::invalid_argument(option + ": " + problem);
}

// CLI11 checks for an option naming an output file or folder (CLI11 adds the option's name).
inline CLI::Validator output_file() {
  return CLI::Validator([](std::string& p) { return output_path_problem(p, false); }, "",
                        "writable output file");
}
inline CLI::Validator output_folder() {
  return CLI::Validator([](std::string& p) { return output_path_problem(p, true); }, "",
                        "writable output folder");
}

}  // namespace shadesim
