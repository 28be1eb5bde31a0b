// The unit's widths as command-line options, shared by every subcommand that builds a unit.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "model/unit_config.h"

namespace shadesim {

struct WidthOptions {
  UnitConfig defaults;
  std::string coef = defaults.coef.to_string();
  std::string series = defaults.series.to_string();
  std::string spec_colour = defaults.spec_colour.to_string();
  std::string spec_out = defaults.specular.out.to_string();
  int out_bits = defaults.out_bits;
  int xy_bits = defaults.xy_bits;

  UnitConfig to_config() const {
    UnitConfig c = defaults;
    c.coef = parse_fixed_format(coef, "--coef");
    c.series = parse_fixed_format(series, "--series");
    c.spec_colour = parse_fixed_format(spec_colour, "--spec-colour");
    c.specular.out = parse_fixed_format(spec_out, "--spec-out");
    c.out_bits = out_bits;
    c.xy_bits = xy_bits;
    c.validate();
    return c;
  }
};

inline void add_width_options(CLI::App& sub, WidthOptions& w) {
  const char* group = "Widths (s|u<integer bits incl. sign>.<fraction bits>[:trn|:rnd][:sat|:wrap])";
  sub.add_option("--coef", w.coef, "triangle Taylor coefficient format")->capture_default_str()->group(group);
  sub.add_option("--series", w.series, "forward-difference accumulator format")->capture_default_str()->group(group);
  sub.add_option("--spec-colour", w.spec_colour, "specular colour format")->capture_default_str()->group(group);
  sub.add_option("--spec-out", w.spec_out, "specular unit output format")->capture_default_str()->group(group);
  sub.add_option("--out-bits", w.out_bits, "output bits per channel")->capture_default_str()->group(group);
  sub.add_option("--xy-bits", w.xy_bits, "screen coordinate bits")->capture_default_str()->group(group);
}

}  // namespace shadesim
