// An RTL configuration as Verilated: its UnitConfig (parsed from the same text CMake turned into
// Verilog parameters, cmake/rtl.cmake) and its deliberate-fault rows.
#pragma once

#include <string>

#include "model/unit_config.h"

namespace shadesim {

struct RtlConfig {
  std::string name;
  UnitConfig unit;
  int fault_lsb_row = -1;
  int fault_stall_row = -1;
};

RtlConfig make_rtl_config(const std::string& name, int channels, int lights, int xy_bits,
                          const std::string& coef, const std::string& series,
                          const std::string& spec_colour, int out_bits,
                          const std::string& specular, const std::string& specular_out,
                          int fault_lsb_row, int fault_stall_row);

}  // namespace shadesim
