// JUnit XML, the format CI systems read test results from.
#pragma once

#include <string>
#include <vector>

namespace shadesim {

struct JUnitCase {
  std::string classname;
  std::string name;
  double seconds = 0;
  std::string failure;  // non-empty: failed with this message
  std::string skipped;  // non-empty: skipped for this reason
};

struct JUnitSuite {
  std::string name;
  std::vector<JUnitCase> cases;
};

// Throws std::runtime_error naming the path when it cannot be written.
void write_junit(const std::string& path, const JUnitSuite& suite);

// XML-escapes text for attributes and element content.
std::string xml_escape(const std::string& text);

}  // namespace shadesim
