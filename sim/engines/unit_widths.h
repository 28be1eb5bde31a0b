// The unit's widths as plain values (what a command was given, as text), turned into a
// UnitConfig by to_config(). The command-line options that fill them: sim/cli/width_options.h.
#pragma once

#include <map>
#include <stdexcept>
#include <string>

#include "model/specular_units.h"
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
  int offset_bits = defaults.offset_bits;
  // Specular unit fields by command-line option (model/specular_units.h): the text as given,
  // parsed in to_config. Fields sharing an option (--fit) are set together.
  std::map<std::string, std::string> unit_fields = default_unit_fields(defaults.specular);

  static std::map<std::string, std::string> default_unit_fields(const SpecularConfig& s) {
    std::map<std::string, std::string> m;
    for (const SpecularUnitDescriptor& u : specular_units()) {
      for (const SpecularField& f : u.fields) {
        if (*f.cli != '\0') m.emplace(f.cli, f.text(s));
      }
    }
    return m;
  }

  UnitConfig to_config() const {
    UnitConfig c = defaults;
    c.coef = parse_fixed_format(coef, "--coef");
    c.series = parse_fixed_format(series, "--series");
    c.spec_colour = parse_fixed_format(spec_colour, "--spec-colour");
    c.specular.out = parse_fixed_format(spec_out, "--spec-out");
    c.out_bits = out_bits;
    c.xy_bits = xy_bits;
    c.offset_bits = offset_bits;
    // Every unit's options are checked, not only the unit the scene will select: a bad value
    // is named by its option here rather than later by its field.
    for (const SpecularUnitDescriptor& u : specular_units()) {
      for (const SpecularField& f : u.fields) {
        if (*f.cli == '\0') continue;
        const int v = f.parse(unit_fields.at(f.cli), f.cli);
        if (!f.in_range(v)) {
          throw std::invalid_argument(std::string(f.cli) + ": must be " + f.expected() + ", got " +
                                      unit_fields.at(f.cli));
        }
        f.set(c.specular, v);
      }
    }
    c.validate();
    return c;
  }
};

}  // namespace shadesim
