// The scenes measured on a trial unit of the derived structure whose formats lose nothing
// (nothing wraps, saturates or is pre-shifted), so the widths fit the values themselves rather
// than what a narrower unit wraps or saturates: every pixel's offsets from its triangle's origin,
// series values and differences, and the coefficients' reach.
#pragma once

#include <array>

#include "derive/derive_config.h"
#include "host/prepared_scene.h"
#include "model/command_stream.h"
#include "model/unit_config.h"

namespace shadesim {

// Numbers measured on one scene's trial frame, merged over scenes.
struct Walk {
  int longest_span = 0, max_offset = 0;
  int start_offset_min = 0, start_offset_max = 0;  // of dx, dy at a span's first pixel
  double monomial_sum = 0, v_min = 0, v_max = 0, diff_max = 0, coef_max = 0;
  std::array<double, kTermsPerSeries> term_max{};  // largest |T_t| of any series
};

// Every scene walked on the trial unit of cfg's structure.
Walk measure_on_trial_unit(const FrameSet& frames, const UnitConfig& cfg);
void record_walk(const Walk& w, ConfigMeasurements& ms);

// What one scene drives on `unit`'s own structure (channels, lights, diffuse colour, specular
// unit), measured as derive_config measures it: on a trial of that structure whose series and
// coefficient formats lose nothing. The figures a given unit's formats are checked against
// (render's warnings); budget_lsb unset: the scene's.
ConfigMeasurements measure_scene_on(const PreparedScene& frame, const UnitConfig& unit);

}  // namespace shadesim
