#include "sim/harness/rtl_config.h"

namespace shadesim {

RtlConfig make_rtl_config(const std::string& name, int channels, int lights, int xy_bits,
                          const std::string& coef, const std::string& series,
                          const std::string& spec_colour, int out_bits,
                          const std::string& specular, const std::string& specular_out,
                          int fault_lsb_row, int fault_stall_row) {
  RtlConfig r;
  r.name = name;
  const std::string what = "rtl config " + name;
  r.unit.channels = channels;
  r.unit.lights = lights;
  r.unit.xy_bits = xy_bits;
  r.unit.coef = parse_fixed_format(coef, what + ": coef");
  r.unit.series = parse_fixed_format(series, what + ": series");
  r.unit.spec_colour = parse_fixed_format(spec_colour, what + ": spec_colour");
  r.unit.out_bits = out_bits;
  r.unit.specular.kind = parse_specular_unit(specular, what + ": specular");
  r.unit.specular.out = parse_fixed_format(specular_out, what + ": specular.out");
  r.unit.validate();
  r.fault_lsb_row = fault_lsb_row;
  r.fault_stall_row = fault_stall_row;
  return r;
}

}  // namespace shadesim
