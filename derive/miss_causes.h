// Why a unit misses its budget on a frame, measured: a cause is named only when re-shading the
// prepared frame with that cause removed brings it within the budget. In order:
//   specular unit     exact pow in place of the unit, on the same formats;
//   formats           formats that lose nothing, with the unit kept;
//   unit and formats  both removed (two causes that add up: neither alone meets it);
//   Taylor setup      the frame prepared again with deeper subdivision, on exact pow and formats
//                     that lose nothing;
//   N.L gate          against a reference whose specular gate is the Taylor series' N.L > 0 (as
//                     the unit gates it) rather than the exact N.L, on exact pow and formats
//                     that lose nothing: the flips at the terminator account for the rest;
//   unknown           none of these: the message says so, with each figure measured.
#pragma once

#include <string>

#include "host/metrics.h"
#include "host/prepared_scene.h"
#include "model/unit_config.h"

namespace shadesim {

enum class MissCause { kSpecularUnit, kFormats, kUnitAndFormats, kTaylorSetup, kGate, kUnknown };

// "specular_unit", "formats", "unit_and_formats", "taylor_setup", "gate", "unknown": the names
// config's JSON and scripts/random-scenes count by.
const char* to_string(MissCause cause);

struct MissExplanation {
  MissCause cause = MissCause::kUnknown;
  int error_removed = 0;  // the frame's error with the cause removed (codes); kUnknown: the least
  std::string text;       // the miss and its cause, with the figures measured
  bool verified() const { return cause != MissCause::kUnknown; }
};

// How much deeper than the frame's depth limit the Taylor setup cause is tried, at most to the
// deepest the CLI's --max-depth takes (so the cause names a depth a user can ask for).
constexpr int kDeeperSubdivision = 4;
constexpr int kDeepestSubdivision = 16;

// Why `unit`, whose image on `frame` has `error` (over the budget), misses it.
MissExplanation explain_miss_cause(const PreparedScene& frame, const UnitConfig& unit,
                                   const ErrorStats& error);

// The prepared frame's error on exactly `unit` against a reference whose specular gate is the
// setup's Taylor N.L > 0 (ShadingVariant::gate_quadratics), in output codes.
int error_against_taylor_gate(const PreparedScene& frame, const UnitConfig& unit);

}  // namespace shadesim
