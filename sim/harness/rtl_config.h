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

// unit_params: the selected specular unit's fields as space-separated key=value pairs, with the
// names of its JSON object (model/command_stream.h config_to_json), e.g.
// "addr_bits=10 entry_bits=8 index=nearest" (lut), "quotient_bits=16 timing=pipelined"
// (schlick), "max_m=16 base_bits=16 timing=iterative" (wpow). Throws std::invalid_argument
// naming the configuration and the key for an unknown key or a bad value.
RtlConfig make_rtl_config(const std::string& name, int channels, int lights, int xy_bits,
                          const std::string& coef, const std::string& series,
                          const std::string& spec_colour, int out_bits,
                          const std::string& specular, const std::string& specular_out,
                          int fault_lsb_row, int fault_stall_row,
                          const std::string& unit_params = "", int port_words = 1,
                          int tri_queue = 1);

}  // namespace shadesim
