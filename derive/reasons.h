// The reasons: why each field of a derived unit has its value, with the measured numbers
// (DerivedConfig::reasons, in config_to_json's order), and the rules that say how in general
// (derivation_rules, which shadesim config --help prints).
#pragma once

#include <string>
#include <vector>

#include "derive/budget.h"
#include "derive/derive_config.h"
#include "derive/throughput_choice.h"
#include "host/prepared_scene.h"
#include "model/unit_config.h"

namespace shadesim {

// Why each derived field has its value, kept until the unit is final (field_reasons lists them).
struct FieldWhys {
  std::string channels, lights, diffuse_colour, specular, xy_bits, offset_bits, series, coef,
      coef_term_iwl, span_setup, spec_colour, specular_out;
};

// The budget's reason, then one per field in config_to_json's order, each value as it writes it.
std::vector<FieldReason> field_reasons(const UnitConfig& cfg, const Budget& budget,
                                       const FieldWhys& why, const ThroughputChoice& throughput);

// The throughput structure chosen again for d.config's widths: the gate's fraction bits widen
// the coefficient and start words, so the port may no longer carry them in time. Replaces the
// knobs, their reasons and the cycles misses.
void rechoose_throughput(const FrameSet& frames, const DeriveOptions& options, DerivedConfig& d);

// Every rule of the derivation (each defined beside the code that applies it), in the order
// config --help prints them. Every field of DerivedConfig::reasons is among some rule's fields.
std::vector<DerivationRule> derivation_rules();

}  // namespace shadesim
