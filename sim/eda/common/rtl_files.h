// The one list of shade_unit's RTL sources: rtl/files.f, file names in dependency order (leaves
// first), one a line, `//` comment lines. CMake reads it too (cmake/rtl_files.cmake).
#pragma once

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace shadesim {

// The sources a folder's files.f lists, as paths in that folder; an error names a missing list.
inline std::vector<std::filesystem::path> rtl_file_list(const std::string& dir) {
  const std::filesystem::path list = std::filesystem::path(dir) / "files.f";
  std::ifstream is(list);
  if (!is) throw std::runtime_error(list.string() + ": cannot read the RTL file list");
  std::vector<std::filesystem::path> out;
  std::string line;
  while (std::getline(is, line)) {
    const auto b = line.find_first_not_of(" \t\r");
    if (b == std::string::npos) continue;
    const auto e = line.find_last_not_of(" \t\r");
    const std::string name = line.substr(b, e - b + 1);
    if (name.rfind("//", 0) == 0) continue;
    out.push_back(std::filesystem::path(dir) / name);
  }
  if (out.empty()) throw std::runtime_error(list.string() + ": lists no RTL sources");
  return out;
}

}  // namespace shadesim
