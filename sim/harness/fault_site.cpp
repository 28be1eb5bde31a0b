#include "sim/harness/fault_site.h"

#include <stdexcept>

namespace shadesim {

const std::vector<FaultSiteInfo>& fault_sites() {
  static const std::vector<FaultSiteInfo> sites = {
      {FaultSite::kLsb, "lsb", "channel 0 of every pixel of the row + 1 LSB"},
      {FaultSite::kStall, "stall", "one extra engine stall before the row's last span"},
      {FaultSite::kHang, "hang", "the engines never take a span of the row"},
      {FaultSite::kChannel2, "ch2", "channel 2 of every pixel of the row + 1 LSB"},
      {FaultSite::kX, "x", "pix_x_o + 1 on the row"},
      {FaultSite::kY, "y", "pix_y_o bit 0 flipped on the row"},
      {FaultSite::kEor, "eor", "pix_eor_o inverted on the row"},
      {FaultSite::kSpanSetup, "setup", "series 0's span start value + 1 output LSB"},
      {FaultSite::kRounding, "round", "the row's output truncated instead of rounded"},
      {FaultSite::kSpecular, "spec", "light 0's specular result, top fraction bit flipped"},
  };
  return sites;
}

std::string FaultInjection::text() const {
  for (const FaultSiteInfo& s : fault_sites()) {
    if (s.site == site) return std::string(s.name) + "@" + std::to_string(row);
  }
  return "";
}

std::vector<std::string> FaultInjection::plusargs() const {
  if (!any()) return {};
  return {"+shadesim_fault=" + std::to_string(static_cast<int>(site)),
          "+shadesim_fault_row=" + std::to_string(row)};
}

VerilatorCommandLine::VerilatorCommandLine(const FaultInjection& fault) : args_(fault.plusargs()) {
  args_.insert(args_.begin(), "cosim");
  for (const std::string& a : args_) argv_.push_back(a.c_str());
}

FaultInjection parse_fault(const std::string& text) {
  std::string names;
  for (const FaultSiteInfo& s : fault_sites())
    names += (names.empty() ? "" : ", ") + std::string(s.name);
  const auto at = text.find('@');
  const std::string expected = "expected SITE@Y with SITE one of " + names + " and Y a row >= 0";
  if (at == std::string::npos) throw std::invalid_argument("fault '" + text + "': " + expected);
  const std::string name = text.substr(0, at), row = text.substr(at + 1);
  FaultInjection f;
  for (const FaultSiteInfo& s : fault_sites()) {
    if (name == s.name) f.site = s.site;
  }
  if (!f.any() || row.empty() || row.size() > 5 ||
      row.find_first_not_of("0123456789") != std::string::npos) {
    throw std::invalid_argument("fault '" + text + "': " + expected);
  }
  f.row = std::stoi(row);
  return f;
}

std::string fault_unsupported(const FaultInjection& fault, const UnitConfig& unit) {
  if (fault.row >= (1 << unit.xy_bits)) {
    return "row " + std::to_string(fault.row) + " is beyond the unit's " +
           std::to_string(unit.xy_bits) + "-bit y";
  }
  if (fault.site == FaultSite::kChannel2 && unit.channels < 3) {
    return "the unit has " + std::to_string(unit.channels) + " channel(s), no channel 2";
  }
  if (fault.site == FaultSite::kSpecular && unit.specular.kind == SpecularUnitKind::kIdeal) {
    return "an ideal unit has no specular hardware (its specular colour is 0)";
  }
  if (fault.site == FaultSite::kSpecular && unit.specular.kind == SpecularUnitKind::kNone) {
    return "a unit with specular kind none has no specular term";
  }
  return "";
}

}  // namespace shadesim
