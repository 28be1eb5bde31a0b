// Where a unit cannot shade a scene within its error budget, say so and why, measured on the unit
// under test (never a silently wrong image). Two kinds of check:
//   formats  each format of the unit against what the scene drives on the unit's own structure
//            (measure_scene_on, derive/trial_unit.h):
//              series range  series values and colour products beyond the series' integer
//                            range wrap or saturate (an overbright light, say);
//              colour words  ks_c L_c (and kd_c L_c multiplied) beyond spec_colour's range
//                            saturate;
//              drift         spans longer than the series fraction bits' drift bound allows
//                            within a quarter of the budget;
//              N.L gate      pixels near the terminator whose specular gate flips against the
//                            widest formats with an output over the budget (host/gate_flips.h).
//            Each names the format, how many values, spans or pixels it affects, and the width
//            that would hold the scene.
//   the miss an image over the budget always gets one warning with its measured error and the
//            cause, named only where re-shading the frame with it removed meets the budget
//            (derive/miss_causes.h), else said to be unknown.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "host/metrics.h"
#include "host/prepared_scene.h"
#include "model/command_stream.h"
#include "model/unit_config.h"

namespace shadesim {

// The formats of `unit` checked against the prepared scene; `stream`: the scene's stream on
// `unit`. The budget and depth limit are the frame's (PreparedScene::key, unset: the scene's).
std::vector<std::string> format_warnings(const PreparedScene& frame, const UnitConfig& unit,
                                         const CommandStream& stream);

// Why `unit`, whose image has `error`, misses the budget (explain_miss_cause's text,
// derive/miss_causes.h). Call it only for an image over the budget.
std::string explain_miss(const PreparedScene& frame, const UnitConfig& unit,
                         const ErrorStats& error);

// format_warnings, and explain_miss where `error` is over the budget; then each format warning
// that names a width also says what the frame re-shaded with that width is (within the budget,
// or still over it: not the whole miss).
std::vector<std::string> accuracy_warnings(const PreparedScene& frame, const UnitConfig& unit,
                                           const CommandStream& stream, const ErrorStats& error);

// A unit with the same structure and specular unit whose series, coefficient, colour and
// specular output formats lose nothing on a scene with colours up to colour_max.
UnitConfig lossless_formats(const UnitConfig& unit, double colour_max);

}  // namespace shadesim
