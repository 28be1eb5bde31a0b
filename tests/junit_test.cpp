// JUnit XML for CI: counts, escaping, and well-formedness of what CI parsers read.
#include "sim/regress/junit.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace shadesim {
namespace {

std::string read(const std::string& path) {
  std::ifstream is(path);
  std::stringstream ss;
  ss << is.rdbuf();
  return ss.str();
}

TEST(JUnit, CountsFailuresAndSkipsAndEscapesText) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "shadesim_junit_test.xml").string();
  JUnitSuite suite{"shadesim.regress", {}};
  suite.cases.push_back({"regress.sphere", "grey.cpp", 0.5, "", ""});
  suite.cases.push_back({"regress.multi", "rgb<2>.cpp", 1.0,
                         "pixel mismatch at y=3 \"x\" & <more>\nreplay: a --b", ""});
  suite.cases.push_back(
      {"regress.multi", "grey.cpp", 0.0, "", "scene has colour; the unit has one channel"});
  write_junit(path, suite);
  const std::string xml = read(path);
  EXPECT_NE(xml.find("tests=\"3\" failures=\"1\" errors=\"0\" skipped=\"1\""), std::string::npos)
      << xml;
  EXPECT_NE(xml.find("name=\"rgb&lt;2&gt;.cpp\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("&quot;x&quot; &amp; &lt;more&gt;"), std::string::npos) << xml;
  // No raw markup characters survive inside attribute values.
  const std::regex attribute("=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), attribute);
       it != std::sregex_iterator(); ++it) {
    const std::string value = (*it)[1];
    EXPECT_EQ(value.find('<'), std::string::npos) << value;
    EXPECT_EQ(value.find('>'), std::string::npos) << value;
  }
  // Every opened testcase element is closed.
  size_t open = 0, closed = 0;
  for (size_t p = xml.find("<testcase"); p != std::string::npos; p = xml.find("<testcase", p + 1))
    ++open;
  for (size_t p = xml.find("</testcase>"); p != std::string::npos;
       p = xml.find("</testcase>", p + 1))
    ++closed;
  for (size_t p = xml.find("/>\n", 0); p != std::string::npos; p = xml.find("/>\n", p + 1))
    ++closed;
  EXPECT_EQ(open + 1, closed) << xml;  // + the skipped element's own "/>"
  std::filesystem::remove(path);
}

TEST(JUnit, UnwritablePathIsAClearError) {
  try {
    write_junit("/nonexistent-dir/x.xml", JUnitSuite{"s", {}});
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.xml"), std::string::npos);
  }
}

}  // namespace
}  // namespace shadesim
