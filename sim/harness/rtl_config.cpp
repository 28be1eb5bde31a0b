#include "sim/harness/rtl_config.h"

#include <sstream>
#include <stdexcept>

namespace shadesim {
namespace {

int to_int(const std::string& value, const std::string& what) {
  size_t used = 0;
  int v = 0;
  try {
    v = std::stoi(value, &used);
  } catch (const std::logic_error&) {
    used = 0;
  }
  if (used == 0 || used != value.size()) throw std::invalid_argument(what + ": expected an integer, got '" + value + "'");
  return v;
}

void apply_unit_param(SpecularConfig& s, const std::string& key, const std::string& value, const std::string& what) {
  const std::string w = what + ": " + key;
  switch (s.kind) {
    case SpecularUnitKind::kLut:
      if (key == "addr_bits") return void(s.lut.addr_bits = to_int(value, w));
      if (key == "entry_bits") return void(s.lut.entry_bits = to_int(value, w));
      if (key == "interp_bits") return void(s.lut.interp_bits = to_int(value, w));
      if (key == "index") return void(s.lut.index = parse_lut_index(value, w));
      if (key == "addressing") return void(s.lut.addressing = parse_lut_addressing(value, w));
      if (key == "shared_range_log2") return void(s.lut.shared_range_log2 = to_int(value, w));
      if (key == "fit") return void(s.lut.fit = parse_fit_objective(value, w));
      break;
    case SpecularUnitKind::kSchlick:
      if (key == "quotient_bits") return void(s.schlick.quotient_bits = to_int(value, w));
      if (key == "operand_bits") return void(s.schlick.operand_bits = to_int(value, w));
      if (key == "timing") return void(s.schlick.timing = parse_unit_timing(value, w));
      if (key == "fit") return void(s.schlick.fit = parse_fit_objective(value, w));
      break;
    case SpecularUnitKind::kWpow:
      if (key == "max_m") return void(s.wpow.max_m = to_int(value, w));
      if (key == "base_bits") return void(s.wpow.base_bits = to_int(value, w));
      if (key == "timing") return void(s.wpow.timing = parse_unit_timing(value, w));
      if (key == "fit") return void(s.wpow.fit = parse_fit_objective(value, w));
      break;
    case SpecularUnitKind::kIdeal:
      break;
  }
  throw std::invalid_argument(what + ": '" + key + "' is not a parameter of the " + to_string(s.kind) + " unit");
}

}  // namespace

RtlConfig make_rtl_config(const std::string& name, int channels, int lights, int xy_bits,
                          const std::string& coef, const std::string& series,
                          const std::string& spec_colour, int out_bits,
                          const std::string& specular, const std::string& specular_out,
                          int fault_lsb_row, int fault_stall_row, const std::string& unit_params,
                          int port_words, int tri_queue) {
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
  std::istringstream is(unit_params);
  std::string pair;
  while (is >> pair) {
    const auto eq = pair.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw std::invalid_argument(what + ": unit parameter '" + pair + "': expected key=value");
    }
    apply_unit_param(r.unit.specular, pair.substr(0, eq), pair.substr(eq + 1), what);
  }
  r.unit.port_words = port_words;
  r.unit.tri_queue = tri_queue;
  r.unit.validate();
  r.fault_lsb_row = fault_lsb_row;
  r.fault_stall_row = fault_stall_row;
  return r;
}

}  // namespace shadesim
