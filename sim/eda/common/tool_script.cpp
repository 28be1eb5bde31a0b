#include "sim/eda/common/tool_script.h"

#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "sim/eda/common/build_paths.h"

namespace shadesim {

std::string tool_script(const std::string& path) {
  const std::string full = source_dir() + "/" + path;
  std::ifstream is(full, std::ios::binary);
  if (!is)
    throw std::runtime_error(full +
                             ": cannot read this tool script (shadesim reads its tools' "
                             "scripts from the checkout it was built from)");
  const std::string text((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>());
  if (is.bad()) throw std::runtime_error(full + ": read failed");
  return script_commands(text);
}

std::string script_commands(const std::string& text) {
  std::istringstream in(text);
  std::string out;
  for (std::string line; std::getline(in, line);) {
    const auto first = line.find_first_not_of(" \t");
    if (first != std::string::npos && line[first] == '#') continue;
    out += line + '\n';
  }
  return out;
}

std::string fill_placeholders(std::string text, const std::map<std::string, std::string>& values) {
  for (const auto& [from, to] : values) {
    for (size_t at = 0; (at = text.find(from, at)) != std::string::npos; at += to.size())
      text.replace(at, from.size(), to);
  }
  return text;
}

}  // namespace shadesim
