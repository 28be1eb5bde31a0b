// A scene's own configuration: the smallest UnitConfig that shades the given scenes within an
// error budget, derived from what the scenes need and from numbers measured on their host setup,
// with one human-readable reason per field. The public entry of derive/; the jobs it runs are one
// file each (docs/architecture.md, Layout): survey (channels, lights, diffuse colour), budget,
// trial_unit (the measurements), width_rules and colour_rules, specular_search,
// throughput_choice, pipelining, reasons. Each rule's text sits beside the code that applies it;
// derivation_rules (derive/reasons.h) lists them, and shadesim config --help prints that list.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "derive/format_widening.h"
#include "derive/specular_candidates.h"
#include "host/prepared_scene.h"
#include "host/scene_error.h"
#include "model/unit_config.h"

namespace shadesim {

// A field added here must join derive_options_json (sim/engines/derivation_key.cpp): the derivation
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
  // Set by derive_config's search where exact pow misses the budget on the derived formats and
  // formats that lose nothing meet it: the fraction bits measured to hold the scenes, added to
  // the width rules' (derive/format_widening.h).
  FormatWidening widen;
  int max_depth = 12;  // setup's subdivision depth limit, as FrameOptions
  // Widen series and coef where the N.L gate flips over the budget (host/gate_flips.h); off for
  // a caller that only reads the measurements.
  bool hold_gate = true;
  // Throughput structure (pixels do not depend on it): requests. Unset, each is derived with
  // the start bank's depth, the material buffers and a Schlick or W_m unit's timing
  // (derive/throughput_choice.h): the cheapest structure that runs every scene within
  // its cycles target (below) by the cycle model (no gaps, no back-pressure). Set, it is held.
  // Host span setup takes tri_queue 1.
  std::optional<int> port_words;
  std::optional<int> tri_queue;
  std::optional<SpanSetupSite> span_setup;
  // Diffuse colour: unset derives it - multiply (one N.L series per light) with three channels,
  // series with one (a multiply would remove nothing there).
  std::optional<DiffuseColour> diffuse_colour;
  // Pixel lanes of the derived unit (UnitConfig::lanes: 1, 2 or 4 pixels of one span a clock;
  // pixels do not depend on them): the throughput structure is chosen to feed them.
  int lanes = 1;
  // The cycles per pixel every scene must stay within. Unset: kMaxCyclesPerBeat (1.10) cycles
  // per beat of `lanes` pixels (cycles_target, derive/throughput_choice.h): 1.10 cycles/px with
  // one lane. Not 1.10 / lanes: lanes stay within a span, so a scene of short spans cannot reach
  // it (sphere_1024 takes 0.304 cycles/px at the least with 4 lanes, over 0.275).
  std::optional<double> max_cycles_per_pixel;
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
// each_measurement (sim/engines/derived_json.cpp), or a cached derivation reads it back as 0.
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
  double gain = 0;              // G (kGainRule, derive/width_rules.h)
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
  // One per scene over its cycles target (cycles_target) on `config`: the scene, its cycles per
  // pixel, the target and the resource that limits it (cycles_miss, derive/throughput_choice.h).
  std::vector<std::string> cycles_misses;
  // Each scene's cycles on `config` (the throughput choice measured them; the closed-form cycle
  // model, as scene_cycles counts them).
  std::vector<SceneCycles> cycles;
};

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

// One rule of the derivation as shadesim config --help states it, defined beside the code that
// applies it (kSeriesRule in derive/width_rules.cpp, ...); derivation_rules (derive/reasons.h)
// lists every one.
struct DerivationRule {
  const char* fields;  // the DerivedConfig::reasons fields it derives, ", " between two
  const char* text;    // the rule, one paragraph
};
extern const DerivationRule kOutBitsRule, kLanesRule, kGateRule;

}  // namespace shadesim
