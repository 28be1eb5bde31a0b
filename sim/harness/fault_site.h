// The deliberate faults of the harness's own tests, as a run chooses them: a site and a row.
// A build with FAULT_HOOKS = 1 (sim/harness/builds.json "fault_hooks") can inject any one of
// them; shade_unit's fault_select reads the choice from the plusargs below. The site numbers
// are the C++ twin of rtl/shade_pkg.sv Fault* (tests/fault_site_test.cpp reads both).
#pragma once

#include <string>
#include <vector>

#include "model/unit_config.h"

namespace shadesim {

enum class FaultSite : int {
  kNone = 0,
  kLsb = 1,        // channel 0 of every pixel of the row + 1 LSB
  kStall = 2,      // one extra engine stall before the row's last_in_row span (first one)
  kHang = 3,       // the engines never take a span of the row: no more pixels
  kChannel2 = 4,   // channel 2 of every pixel of the row + 1 LSB
  kX = 5,          // pix_x_o + 1 on the row
  kY = 6,          // pix_y_o bit 0 flipped on the row
  kEor = 7,        // pix_eor_o inverted on the row
  kSpanSetup = 8,  // series 0's start value + 1 output LSB for the row's spans
  kRounding = 9,   // the row's output truncated instead of rounded
  kSpecular = 10,  // light 0's specular result with its top fraction bit flipped on the row
};

struct FaultInjection {
  FaultSite site = FaultSite::kNone;
  int row = 0;

  bool any() const { return site != FaultSite::kNone; }
  std::string text() const;                   // "lsb@17", or "" for none
  std::vector<std::string> plusargs() const;  // +shadesim_fault=N +shadesim_fault_row=Y
};

// The command line a Verilated model is given (Verilated's commandArgs): a program name and the
// fault's plusargs, which shade_unit's fault_select reads at time 0.
class VerilatorCommandLine {
 public:
  explicit VerilatorCommandLine(const FaultInjection& fault);
  VerilatorCommandLine(const VerilatorCommandLine&) = delete;  // argv_ points into args_
  VerilatorCommandLine& operator=(const VerilatorCommandLine&) = delete;
  int argc() const { return static_cast<int>(argv_.size()); }
  const char** argv() { return argv_.data(); }

 private:
  std::vector<std::string> args_;
  std::vector<const char*> argv_;  // into args_
};

// "SITE@Y", e.g. "ch2@40". Throws std::invalid_argument naming the sites on anything else.
FaultInjection parse_fault(const std::string& text);

// Every site with its name and what it does, for help text and errors.
struct FaultSiteInfo {
  FaultSite site;
  const char* name;
  const char* what;
};
const std::vector<FaultSiteInfo>& fault_sites();

// Why `unit` cannot show the fault (a site that changes nothing there), or "" when it can.
std::string fault_unsupported(const FaultInjection& fault, const UnitConfig& unit);

}  // namespace shadesim
