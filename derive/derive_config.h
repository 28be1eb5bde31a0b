// A scene's own configuration: the smallest UnitConfig that shades the given scenes within an
// error budget, derived from what the scenes need and from numbers measured on their host setup,
// with one human-readable reason per field.
//
// The rules (shadesim config --help states the same):
//   channels, lights   1 channel if every scene is grey, else 3; lights = the most any scene has.
//   specular           none when no material of any scene has a specular term (specular colour
//                      times light colour is 0 in every channel): no unit and no specular series;
//                      else the unit the scenes' materials name; `ideal` is not hardware (its RTL
//                      slot outputs 0), so a scene naming it gets DeriveOptions::ideal_substitute,
//                      or, where that misses the budget on the scenes (measured: max code error
//                      <= budget), the first of DeriveOptions::ideal_fallbacks that meets it, each
//                      with its own widths; a named lut, schlick or wpow unit whose defaults miss
//                      gets the first of its kind's fields that meets it
//                      (derive/specular_candidates.h). Budget first: the first within the budget
//                      whose cycles stay within max(target, the first unit's + 1 %), else the
//                      first within the budget all the same (its cycles stated), else the
//                      closest, with what limits it named.
//   spec_colour        integer: every colour word (ks_c L_c; kd_c L_c multiplied) unsaturated;
//                      fraction: each word's rounding (and, multiplied, N.L truncated to its
//                      fraction bits times kd_c L_c) summed over the lights within 3/16 of the
//                      budget, at least the default's.
//   specular out       fraction: truncation times the summed ks_c L_c within budget/16, at least
//                      the default's.
//   xy_bits            enough unsigned bits for the widest / tallest image (at least 4).
//   series integer     the fewest (>= 2) that hold every series value at every pixel (and every
//                      ambient word), measured on a trial unit wide enough that setup pre-shifts
//                      nothing, and every colour product PixelCombine brings into the series
//                      format; with :sat also every difference d and d2.
//   series fraction    the drift bound of the forward differences over the longest span L,
//                      2^-F (1 + L(L-1)/2) with truncation (half with rounding), times the gain G
//                      of the series into one output channel, within a quarter of the budget.
//   coef integer       wrapping: the series' integer bits (span setup multiplies coefficients
//                      only by integers, so the sums are exact modulo 2^iwl, and UnitConfig needs
//                      coef.iwl >= series.iwl); saturating: the measured coefficient range.
//   coef fraction      coefficient rounding error (2^-(F+1), 2^-F truncating) times the largest
//                      sum of |monomials| 1+|dx|+|dy|+dx^2+|dx dy|+dy^2 at any pixel from its
//                      triangle's origin, times G, within another quarter of the budget.
//   out_bits           as requested.
//   port_words, tri_queue, span_setup, start_depth, material_buffers, a Schlick or W_m
//                      unit's timing: the cheapest structure whose frames all run at <=
//                      DeriveOptions::max_cycles_per_pixel by the cycle model, else the fastest
//                      with each miss named (derive/throughput_choice.h has the cost order);
//                      pixels do not depend on them.
//   diffuse_colour     multiply with three channels (one N.L series per light, a multiply per
//                      light and channel in the unit), series with one.
// G = sum over lights of (1 + max spec colour x the specular unit's slope with respect to its
// series): a diffuse series enters the output with gain 1 (colour is rolled in; multiplied, with
// the largest kd_c L_c instead of 1), a specular one
// through the unit (t^n has slope <= n on [0, 1]; see unit_slope in scene_config.cpp).
// The Taylor error keeps the whole budget in setup (subdivision); the fixed-point error gets
// 3/4 of it on top, so the real error stays below 1.75 budget + output rounding. The shares
// bound the worst case; what counts is measured (config shades every scene on the unit).
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "host/prepared_scene.h"
#include "host/scene_error.h"
#include "derive/specular_candidates.h"
#include "model/unit_config.h"

namespace shadesim {

// A field added here must join derive_options_json (sim/jobs/derivation_key.cpp): the derivation
// cache keys on every field.
struct DeriveOptions {
  std::optional<double> budget_lsb;  // unset: the smallest error_budget_lsb of the scenes
  int out_bits = 8;
  // The hardware unit for scenes whose materials name `ideal`: W_16, B = 16, pipelined, the
  // closest hardware unit to ideal in the README's table.
  SpecularConfig ideal_substitute = [] {
    SpecularConfig s;
    s.kind = SpecularUnitKind::kWpow;
    s.wpow.max_m = 16;
    s.wpow.base_bits = 16;
    s.wpow.timing = UnitTiming::kPipelined;
    return s;
  }();
  // Tried in order when ideal_substitute misses the budget: W_16 with zeta fitted, W_32, then
  // LUTs with linear interpolation (derive/specular_candidates.h; docs/specular.md measures their
  // error and area).
  std::vector<SpecularConfig> ideal_fallbacks = ideal_stand_ins();
  // Scenes naming a hardware unit: search that kind's fields (derive/specular_candidates.h) where
  // its defaults miss the budget; false keeps the defaults.
  bool search_named_units = true;
  // Set by derive_config's search: the specular unit to derive the widths for, in place of the
  // one the scenes name (or ideal's substitute).
  std::optional<SpecularConfig> specular_trial;
  int max_depth = 12;  // setup's subdivision depth limit, as FrameOptions
  // Widen series and coef where the N.L gate flips over the budget (host/gate_flips.h); off for
  // a caller that only reads the measurements.
  bool hold_gate = true;
  // Throughput structure (pixels do not depend on it): requests. Unset, each is derived with
  // the start bank's depth, the material buffers and a Schlick or W_m unit's timing
  // (derive/throughput_choice.h): the cheapest structure that runs every scene within
  // max_cycles_per_pixel by the cycle model (no gaps, no back-pressure). Set, it is held.
  // Host span setup takes tri_queue 1.
  std::optional<int> port_words;
  std::optional<int> tri_queue;
  std::optional<SpanSetupSite> span_setup;
  // Diffuse colour: unset derives it - multiply (one N.L series per light) with three channels,
  // series with one (a multiply would remove nothing there).
  std::optional<DiffuseColour> diffuse_colour;
  double max_cycles_per_pixel = 1.10;
  // Threads that evaluate candidate units side by side (0: the hardware's). The unit and every
  // reason are the same for any count.
  int threads = 0;
};

struct FieldReason {
  std::string field;   // UnitConfig JSON path: "channels", "series", "specular", ...
  std::string value;   // as config_to_json writes it
  std::string reason;  // how it was derived, with the measured numbers
};

// What derive_config measured over all scenes (on the trial unit). A field added here joins
// each_measurement (sim/jobs/derived_json.cpp), or a cached derivation reads it back as 0.
struct ConfigMeasurements {
  double budget_lsb = 0;
  int max_width = 0, max_height = 0;
  int longest_span = 0;                   // pixels
  int max_offset = 0;                     // max |dx|, |dy| of a pixel from its triangle's origin
  int start_offset_min = 0;               // smallest dx or dy of a span's first pixel
  int start_offset_max = 0;               // largest (span setup's offsets)
  double max_monomial_sum = 0;            // max of 1+|dx|+|dy|+dx^2+|dx dy|+dy^2 over pixels
  double series_min = 0, series_max = 0;  // every series value at a pixel, and ambient words
  double difference_max = 0;              // max |d|, |d2|
  double colour_max = 0;                  // largest colour word (ks_c L_c; kd_c L_c multiplied)
  double product_max = 0;       // largest colour product (a colour word times intensity or N.L)
  double coef_max = 0;          // max |T_k| over all triangles and series
  double gain = 0;              // G (see above)
  double drift_share_lsb = 0;   // output LSBs allowed for drift (budget / 4)
  double coef_share_lsb = 0;    // output LSBs allowed for coefficient rounding (budget / 4)
  double colour_share_lsb = 0;  // for the colour words' rounding (3/16 of the budget)
  double specular_out_share_lsb = 0;  // for the specular unit's output truncation (budget / 16)
};

struct DerivedConfig {
  UnitConfig config;
  // "budget" first (where it came from, how it is shared), then one per top-level UnitConfig
  // field in config_to_json's order.
  std::vector<FieldReason> reasons;
  ConfigMeasurements measured;
  bool substitute = false;  // the scenes name ideal; config.specular is the hardware in its place
  // One per scene over DeriveOptions::max_cycles_per_pixel on `config`: the scene, its cycles per
  // pixel, the target and the resource that limits it (cycles_miss, derive/throughput_choice.h).
  std::vector<std::string> cycles_misses;
  // Each scene's cycles on `config` (the throughput choice measured them; the closed-form cycle
  // model, as scene_cycles counts them).
  std::vector<SceneCycles> cycles;
};

// The largest output-code error a budget allows: codes differ by whole LSBs, and rounding the
// model and the reference each to a code makes 1 LSB of difference from any real error, so a
// budget of B LSB allows ceil(B) (0.9 and 1 both allow 1).
inline int code_budget(double budget_lsb) { return static_cast<int>(std::ceil(budget_lsb)); }

// Throws SceneError for bad scenes and std::invalid_argument for scenes no one unit can shade
// (different specular units: the message names the scenes and units) or impossible budgets.
DerivedConfig derive_config(const std::vector<std::string>& scene_paths,
                            const DeriveOptions& options);
// The same on scenes already prepared under prepare_key(options); every candidate unit only
// re-encodes and re-shades them.
DerivedConfig derive_config(const FrameSet& frames, const DeriveOptions& options);

// What a derivation's frames are prepared under: its budget, depth limit and output width.
PrepareKey prepare_key(const DeriveOptions& options);
// Throws std::invalid_argument for no scenes or a budget that is not a positive number: checked
// before any scene is prepared under it.
void check_derive_options(const std::vector<std::string>& scene_paths,
                          const DeriveOptions& options);

// A unit's pipelining, the knobs a clock target turns (pixels do not depend on them):
// UnitConfig::combine_stages and, on a pipelined W_m unit, WpowConfig::square_stages.
struct Pipelining {
  int combine_stages = 0;
  int square_stages = 1;
  std::string describe() const;  // "combine_stages 2, square_stages 2"
};
// The ladder a clock target climbs for `unit`, each rung more registers than the one before:
// combine_stages 0, 1, 2, then (a pipelined W_m unit) square_stages 2.
std::vector<Pipelining> pipelining_ladder(const UnitConfig& unit);
Pipelining pipelining_of(const UnitConfig& unit);

// `derived` pipelined as `p`: the throughput structure is chosen again for it (a register stage
// delays each frame's last pixels by a cycle) and a "combine_stages" reason with `why` joins the
// others. Pixels do not change.
void pipeline_unit(const FrameSet& frames, const DeriveOptions& options, const Pipelining& p,
                   const std::string& why, DerivedConfig& derived);

// What one scene drives on `unit`'s own structure (channels, lights, diffuse colour, specular
// unit), measured as derive_config measures it: on a trial of that structure whose series and
// coefficient formats lose nothing. The figures a given unit's formats are checked against
// (render's warnings); budget_lsb unset: the scene's.
ConfigMeasurements measure_scene_on(const PreparedScene& frame, const UnitConfig& unit);

// The fraction bits F the drift bound asks for: the smallest F with
// gain * 2^-F (1 + L(L-1)/2) [/ 2 when rounding] <= share_lsb * 2^-out_bits.
int drift_fraction_bits(int longest_span, double gain, double share_lsb, int out_bits,
                        bool rounding);

}  // namespace shadesim
