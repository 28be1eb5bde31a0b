#include "sim/regress/junit.h"

#include <sstream>

#include "model/text_file.h"

namespace shadesim {

std::string xml_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char ch : text) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        // Control characters other than tab/newline are not allowed in XML 1.0.
        if (static_cast<unsigned char>(ch) < 0x20 && ch != '\n' && ch != '\t' && ch != '\r') {
          out += '?';
        } else {
          out += ch;
        }
    }
  }
  return out;
}

void write_junit(const std::string& path, const JUnitSuite& suite) {
  size_t failures = 0, skipped = 0;
  double total = 0;
  for (const auto& c : suite.cases) {
    failures += !c.failure.empty();
    skipped += !c.skipped.empty();
    total += c.seconds;
  }
  std::ostringstream os;
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
     << "<testsuites>\n<testsuite name=\"" << xml_escape(suite.name) << "\" tests=\""
     << suite.cases.size() << "\" failures=\"" << failures << "\" errors=\"0\" skipped=\""
     << skipped << "\" time=\"" << total << "\">\n";
  for (const auto& c : suite.cases) {
    os << "  <testcase classname=\"" << xml_escape(c.classname) << "\" name=\""
       << xml_escape(c.name) << "\" time=\"" << c.seconds << "\"";
    if (c.failure.empty() && c.skipped.empty()) {
      os << "/>\n";
      continue;
    }
    os << ">\n";
    if (!c.failure.empty()) {
      os << "    <failure message=\"" << xml_escape(c.failure.substr(0, c.failure.find('\n')))
         << "\">" << xml_escape(c.failure) << "</failure>\n";
    }
    if (!c.skipped.empty()) os << "    <skipped message=\"" << xml_escape(c.skipped) << "\"/>\n";
    os << "  </testcase>\n";
  }
  os << "</testsuite>\n</testsuites>\n";
  write_text_file(path, os.str());
}

}  // namespace shadesim
