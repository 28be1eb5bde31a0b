#include "derive/derive_config.h"

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "derive/budget.h"
#include "derive/colour_rules.h"
#include "derive/reasons.h"
#include "derive/specular_search.h"
#include "derive/survey.h"
#include "derive/throughput_choice.h"
#include "derive/trial_unit.h"
#include "derive/width_rules.h"
#include "host/gate_flips.h"
#include "host/parallel.h"

namespace shadesim {

const DerivationRule kOutBitsRule = {"out_bits", "as requested (--out-bits)"};
const DerivationRule kLanesRule = {
    "lanes",
    "as requested (--lanes 1, 2 or 4: pixels of one span a clock; pixels do not depend "
    "on them)"};

namespace {

// The search's widening (DeriveOptions::widen) on top of the rules' widths, said on each line.
void widen_formats(const FormatWidening& w, UnitConfig& cfg, FieldWhys& why) {
  if (!w.any()) return;
  cfg = widened(cfg, w);
  const std::string measured =
      " fraction bits: exact pow on the rules' formats misses the budget "
      "on the scenes (" +
      std::to_string(w.exact_before) + " LSB), and with " + w.describe() + " meets it (" +
      std::to_string(w.exact_after) + " LSB, measured)";
  auto add = [&measured](std::string& text, int bits) {
    if (bits > 0) text += "; widened by " + std::to_string(bits) + measured;
  };
  add(why.spec_colour, w.spec_colour);
  add(why.specular_out, w.specular_out);
  add(why.series, w.series_coef);
  add(why.coef, w.series_coef);
}

// Every field for one specular substitute (options.ideal_substitute); derive_config below tries
// the fallbacks.
DerivedConfig derive_widths(const FrameSet& frames, const DeriveOptions& options) {
  const std::vector<SceneInfo> scenes = load_scenes(frames);
  const Budget budget = choose_budget(scenes, options);
  DerivedConfig out;
  ConfigMeasurements& ms = out.measured;
  set_budget(budget.lsb, ms);
  UnitConfig& cfg = out.config;  // quantization and overflow rules and unit widths: the defaults
  cfg.out_bits = options.out_bits;
  FieldWhys why;
  why.channels = derive_channels(scenes, cfg);
  why.lights = derive_lights(scenes, cfg);
  why.diffuse_colour = derive_diffuse_colour(options, cfg);
  const SpecularChoice specular = choose_specular_unit(scenes, options, cfg);
  out.substitute = specular.substitute;
  why.specular = specular.why;
  why.xy_bits = derive_xy_bits(scenes, cfg, ms);
  why.spec_colour = derive_spec_colour(scenes, ms, cfg);
  why.specular_out = derive_specular_out(scenes, ms, cfg);
  const Walk w = measure_on_trial_unit(frames, cfg);
  record_walk(w, ms);
  why.offset_bits = derive_offset_bits(w, cfg);
  why.series = derive_series(scenes, w, ms, cfg);
  why.coef = derive_coef(w, ms, cfg);
  why.coef_term_iwl = derive_term_widths(w, cfg);
  widen_formats(options.widen, cfg, why);
  // Lanes change no pixel (the series wrap; docs/throughput.md), so the widths above hold for
  // any count; the structure below is chosen for them.
  cfg.lanes = options.lanes;
  cfg.validate();
  const ThroughputChoice throughput = choose_throughput(frames, options, cfg);
  cfg = throughput.config;
  out.cycles_misses = throughput.misses;
  out.cycles = throughput.cycles;
  out.reasons = field_reasons(cfg, budget, why, throughput);
  return out;
}

}  // namespace

const DerivationRule kGateRule = {
    "series, coef",
    "then, where the derived widths flip the N.L gate near the terminator (specular on or off) "
    "against the widest formats with an output over the budget on a scene (measured), both get "
    "the fraction bits that hold every scene's gate"};

namespace {

// The N.L gate's step (host/gate_flips.h): where the derived widths flip a scene's gate with an
// output over the budget, series and coef get the fraction bits that hold every scene's gate.
void hold_the_gate(const FrameSet& frames, const DeriveOptions& options, DerivedConfig& d) {
  int bits = 0;
  std::string why;
  for (size_t i = 0; i < frames.size(); ++i) {
    const std::string& path = frames.path(i);
    const GateFlips f = measure_gate_flips(
        frames.at(i), d.config, code_budget(d.measured.budget_lsb), thread_count(options.threads));
    if (f.pixels == 0 || f.fix_bits <= bits) continue;  // fix_bits -1: no width holds it
    bits = f.fix_bits;
    why = "; +" + std::to_string(bits) +
          " fraction bits for the N.L gate: " + std::to_string(f.pixels) + " pixel(s) of " + path +
          " near the terminator flipped it against the widest formats, up to " +
          std::to_string(f.max_lsb) + " LSB off, and these hold it";
  }
  if (bits == 0) return;
  d.config = with_more_fraction_bits(d.config, bits);
  const auto json = nlohmann::json::parse(config_to_json(d.config));
  for (auto& r : d.reasons) {
    if (r.field != "series" && r.field != "coef") continue;
    r.value = json.at(r.field).get<std::string>();
    r.reason += why;
  }
}

// derive_widths, with the gate held (and the throughput structure chosen for its widths).
DerivedConfig derive_held(const FrameSet& frames, const DeriveOptions& options) {
  DerivedConfig d = derive_widths(frames, options);
  if (!options.hold_gate) return d;
  const std::string before = config_to_json(d.config);
  hold_the_gate(frames, options, d);
  if (config_to_json(d.config) != before) rechoose_throughput(frames, options, d);
  return d;
}

}  // namespace

DerivedConfig derive_config(const FrameSet& frames, const DeriveOptions& options) {
  return search_specular_unit(frames, options,
                              [&frames](const DeriveOptions& o) { return derive_held(frames, o); });
}

PrepareKey prepare_key(const DeriveOptions& options) {
  return {options.budget_lsb, options.max_depth, options.out_bits};
}

void check_derive_options(const std::vector<std::string>& scene_paths,
                          const DeriveOptions& options) {
  if (scene_paths.empty()) throw std::invalid_argument("derive_config: no scenes given");
  if (options.budget_lsb) check_budget(*options.budget_lsb);
  if (options.lanes != 1 && options.lanes != 2 && options.lanes != 4)
    throw std::invalid_argument("derive_config: lanes must be 1, 2 or 4, got " +
                                std::to_string(options.lanes));
}

DerivedConfig derive_config(const std::vector<std::string>& scene_paths,
                            const DeriveOptions& options) {
  check_derive_options(scene_paths, options);
  PreparedScenes frames;
  return derive_config(FrameSet(frames, scene_paths, prepare_key(options)), options);
}

}  // namespace shadesim
