// Output paths checked before any work starts: every option that names a file or a
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
// (folder = true); "" when it can. Tries it for real without creating or removing any folder:
// where folders are missing, a probe file is created and deleted in the nearest one that exists
// (the missing ones will be made there); else the file is opened for appending, or a probe file
// is created and deleted in the folder. An existing file is left unchanged and a new path leaves
// nothing behind.
// No folder is made and removed again: several processes started at once with outputs under
// one new folder (the shards of a Slurm job array, `--out run/shardN`) would each remove the
// folder the others had just seen, or made, and were about to write into (their
// create_directories then failed with "No such file or directory").
inline std::string output_path_problem(const std::string& path, bool folder) {
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
  const std::string probe = ".shadesim-write-check-" + std::to_string(getpid());
  const fs::path file = !missing.empty() ? existing / probe : folder ? target / probe : target;
  const bool existed = fs::exists(file, ec);
  std::FILE* f = std::fopen(file.c_str(), "a");
  if (f == nullptr) {
    const std::string why = std::strerror(errno);
    if (!missing.empty()) return "cannot create the folder " + missing.back().string() + ": " + why;
    return "cannot write " + (folder ? "into the folder " + target.string() : target.string()) +
           ": " + why;
  }
  std::fclose(f);
  if (!existed) fs::remove(file, ec);
  return "";
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
