// A whole text file written in one go (reports, configurations, job lists): every error names
// the file, and a write that fails part-way is an error, not a short file.
#pragma once

#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace shadesim {

inline void write_text_file(const std::string& path, std::string_view text) {
  std::ofstream os(path);
  if (!os) throw std::runtime_error(path + ": cannot open for writing");
  os << text;
  os.flush();
  if (!os) throw std::runtime_error(path + ": write failed");
}

}  // namespace shadesim
