// A whole text file read or written in one go (logs, reports, configurations, job lists): every
// error names the file, and a write that fails part-way is an error, not a short file.
#pragma once

#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>

namespace shadesim {

// The whole file; an error names it.
inline std::string read_text_file(const std::string& path) {
  std::ifstream is(path, std::ios::binary);
  if (!is) throw std::runtime_error(path + ": cannot read");
  std::string text((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>());
  if (is.bad()) throw std::runtime_error(path + ": read failed");
  return text;
}

// Up to the first newline (a tool's version line, a log's first line).
inline std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

inline void write_text_file(const std::string& path, std::string_view text) {
  std::ofstream os(path);
  if (!os) throw std::runtime_error(path + ": cannot open for writing");
  os << text;
  os.flush();
  if (!os) throw std::runtime_error(path + ": write failed");
}

}  // namespace shadesim
