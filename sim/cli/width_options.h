// The unit's widths as command-line options, shared by every subcommand that builds a unit; they
// fill a WidthOptions (sim/engines/unit_widths.h).
#pragma once

#include <CLI/CLI.hpp>
#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "model/specular_units.h"
#include "sim/engines/unit_widths.h"

namespace shadesim {

// The option groups add_width_options fills (--config excludes every option in them).
constexpr const char* kWidthGroup =
    "Widths (s|u<integer bits incl. sign>.<fraction bits>[:trn|:rnd][:sat|:wrap]; a mode "
    "not written means what SystemC's sc_fix means: :trn and :wrap)";
constexpr const char* kUnitWidthGroup =
    "Specular unit widths (see shadesim spec-error for their error and cost)";

inline void add_width_options(CLI::App& sub, WidthOptions& w) {
  const char* group = kWidthGroup;
  sub.add_option("--coef", w.coef, "triangle Taylor coefficient format")
      ->capture_default_str()
      ->group(group);
  sub.add_option("--series", w.series, "forward-difference accumulator format")
      ->capture_default_str()
      ->group(group);
  sub.add_option("--spec-colour", w.spec_colour, "specular colour format")
      ->capture_default_str()
      ->group(group);
  sub.add_option("--spec-out", w.spec_out, "specular unit output format")
      ->capture_default_str()
      ->group(group);
  sub.add_option("--out-bits", w.out_bits, "output bits per channel")
      ->capture_default_str()
      ->group(group);
  sub.add_option("--xy-bits", w.xy_bits, "screen coordinate bits")
      ->capture_default_str()
      ->group(group);
  sub.add_option("--offset-bits", w.offset_bits,
                 "span setup's signed offset bits (a span's start from its triangle's origin); "
                 "the encoder re-origins triangles beyond them")
      ->capture_default_str()
      ->group(group);
  // One option per distinct flag of the unit table; an option that several units share (--fit)
  // comes after the units' own ones.
  std::vector<const SpecularField*> own, shared;
  std::map<std::string, int> uses;
  for (const SpecularUnitDescriptor& u : specular_units()) {
    for (const SpecularField& f : u.fields) {
      if (*f.cli != '\0' && uses[f.cli]++ == 0) own.push_back(&f);
    }
  }
  for (const SpecularField* f : own) {
    if (uses[f->cli] > 1) shared.push_back(f);
  }
  own.erase(std::remove_if(own.begin(), own.end(),
                           [&](const SpecularField* f) { return uses[f->cli] > 1; }),
            own.end());
  own.insert(own.end(), shared.begin(), shared.end());
  for (const SpecularField* f : own) {
    const std::string help = std::string(f->help) + " (" + f->expected() + ")";
    sub.add_option(f->cli, w.unit_fields.at(f->cli), help)
        ->capture_default_str()
        ->type_name(f->is_enum() ? "TEXT" : "INT")
        ->group(kUnitWidthGroup);
  }
}

}  // namespace shadesim
