// The deliberate-fault sites (sim/harness/fault_site.h): the numbers are fault_pkg.sv's,
// read from the file, and --fault's text form is checked.
#include "sim/harness/fault_site.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>

namespace shadesim {
namespace {

// sim/harness/faults/fault_pkg.sv's `localparam logic [3:0] FaultName = 4'dN;` lines, by name.
std::map<std::string, int> rtl_fault_sites() {
  std::ifstream in(std::string(SHADESIM_SOURCE_DIR) + "/sim/harness/faults/fault_pkg.sv");
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  std::map<std::string, int> sites;
  const std::regex line(R"(localparam\s+logic\s+\[3:0\]\s+Fault(\w+)\s*=\s*4'd(\d+);)");
  for (auto it = std::sregex_iterator(s.begin(), s.end(), line); it != std::sregex_iterator(); ++it)
    sites[(*it)[1]] = std::stoi((*it)[2]);
  return sites;
}

TEST(FaultSite, NumbersAreFaultPkgs) {
  const std::map<std::string, int> rtl = rtl_fault_sites();
  // The RTL's names for the C++ sites (FaultNone is 0, FaultInjection's default).
  const std::map<FaultSite, std::string> rtl_name = {{FaultSite::kLsb, "Lsb"},
                                                     {FaultSite::kStall, "Stall"},
                                                     {FaultSite::kHang, "Hang"},
                                                     {FaultSite::kChannel2, "Channel2"},
                                                     {FaultSite::kX, "X"},
                                                     {FaultSite::kY, "Y"},
                                                     {FaultSite::kEor, "Eor"},
                                                     {FaultSite::kSpanSetup, "SpanSetup"},
                                                     {FaultSite::kRounding, "Rounding"},
                                                     {FaultSite::kSpecular, "Specular"}};
  ASSERT_EQ(rtl.size(), fault_sites().size() + 1) << "a site on one side only";
  EXPECT_EQ(rtl.at("None"), 0);
  for (const FaultSiteInfo& s : fault_sites()) {
    ASSERT_TRUE(rtl_name.count(s.site)) << s.name;
    ASSERT_TRUE(rtl.count(rtl_name.at(s.site))) << rtl_name.at(s.site);
    EXPECT_EQ(rtl.at(rtl_name.at(s.site)), static_cast<int>(s.site)) << s.name;
  }
}

TEST(FaultSite, TextFormAndPlusargs) {
  const FaultInjection f = parse_fault("ch2@40");
  EXPECT_EQ(f.site, FaultSite::kChannel2);
  EXPECT_EQ(f.row, 40);
  EXPECT_EQ(f.text(), "ch2@40");
  EXPECT_EQ(f.plusargs(),
            (std::vector<std::string>{"+shadesim_fault=4", "+shadesim_fault_row=40"}));
  EXPECT_TRUE(FaultInjection{}.plusargs().empty());
  for (const FaultSiteInfo& s : fault_sites()) {
    const std::string text = std::string(s.name) + "@7";
    EXPECT_EQ(parse_fault(text).text(), text);
  }
  for (const char* bad : {"", "lsb", "lsb@", "lsb@-1", "lsb@1x", "nope@3", "@3", "lsb@9999999"}) {
    try {
      parse_fault(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("expected SITE@Y with SITE one of lsb, stall"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(FaultSite, RefusedWhereTheUnitCannotShowIt) {
  UnitConfig grey;
  grey.channels = 1;
  EXPECT_NE(fault_unsupported(parse_fault("ch2@3"), grey).find("no channel 2"), std::string::npos);
  EXPECT_NE(fault_unsupported(parse_fault("spec@3"), grey).find("ideal"), std::string::npos);
  EXPECT_NE(fault_unsupported(parse_fault("lsb@5000"), grey).find("beyond"), std::string::npos);
  EXPECT_EQ(fault_unsupported(parse_fault("lsb@3"), grey), "");
  UnitConfig rgb;
  rgb.channels = 3;
  EXPECT_EQ(fault_unsupported(parse_fault("ch2@3"), rgb), "");
}

}  // namespace
}  // namespace shadesim
