// What a printed command line needs: one shell word per argument, and this shadesim's own path
// (for replay lines, job lists and the commands report --run and explore --verify start).
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

namespace shadesim {

// `text` as one POSIX shell word: as it is when it holds only [A-Za-z0-9_./:=@,+%-], else in
// single quotes (a quote inside written '\'').
inline std::string shell_word(const std::string& text) {
  bool plain = !text.empty();
  for (char c : text) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    std::string("_./:=@,+%-").find(c) != std::string::npos;
    plain = plain && ok;
  }
  if (plain) return text;
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// The path of the running shadesim executable (Linux: /proc/self/exe). `what` names the caller
// in the error (e.g. "--emit-jobs").
inline std::filesystem::path self_executable(const std::string& what) {
  std::error_code ec;
  std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec)
    throw std::runtime_error(what + ": cannot find this shadesim executable: " + ec.message());
  return self;
}

}  // namespace shadesim
