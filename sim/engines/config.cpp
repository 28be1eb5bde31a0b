// shadesim config's engine (its options: sim/cli/config.cpp): derive the smallest unit that shades
// the scenes within the error budget (derive/derive_config.h), print each field with how it was
// derived, and the error the bit-accurate model reaches on each scene with it.
#include "sim/engines/config.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "derive/accuracy_checks.h"
#include "derive/budget.h"
#include "derive/derive_config.h"
#include "derive/miss_causes.h"
#include "host/frame.h"
#include "host/metrics.h"
#include "host/reference.h"
#include "host/scene_error.h"
#include "model/command_stream.h"
#include "model/shade_unit.h"
#include "model/specular_units.h"
#include "model/text_file.h"
#include "sim/engines/clock_target.h"
#include "sim/engines/derivation_cache.h"

namespace shadesim {
namespace {

DeriveOptions derive_options(const ConfigOptions& o) {
  DeriveOptions d;
  if (!std::isnan(o.budget_lsb)) d.budget_lsb = o.budget_lsb;
  d.out_bits = o.out_bits;
  if (o.port_words > 0) d.port_words = o.port_words;
  if (o.tri_queue > 0) d.tri_queue = o.tri_queue;
  d.lanes = o.lanes;
  if (!std::isnan(o.max_cycles_per_pixel)) d.max_cycles_per_pixel = o.max_cycles_per_pixel;
  if (!o.span_setup.empty()) d.span_setup = parse_span_setup(o.span_setup, "--span-setup");
  if (!o.diffuse_colour.empty())
    d.diffuse_colour = parse_diffuse_colour(o.diffuse_colour, "--diffuse-colour");
  if (!o.ideal_unit.empty()) {
    const SpecularUnitKind ideal_as = parse_specular_unit(o.ideal_unit, "--ideal-unit");
    if (ideal_as != d.ideal_substitute.kind) {
      d.ideal_substitute = SpecularConfig{};  // that unit's default widths
      d.ideal_substitute.kind = ideal_as;
    }
    d.ideal_fallbacks.clear();  // the unit asked for, and no other
  }
  return d;
}

// The unit (with whether its derivation was reused: `origin`), and each field with how it was
// derived.
void print_derivation(const DerivedConfig& derived, const std::string& origin) {
  std::cout << "unit         " << derived.config.to_string() << "  (" << origin << ")\n\n";
  size_t width = 0;
  for (const auto& r : derived.reasons)
    width = std::max(width, r.field.size() + r.value.size() + 3);
  for (const auto& r : derived.reasons) {
    std::cout << "  " << std::left << std::setw(static_cast<int>(width))
              << (r.field + " = " + r.value) << "  " << r.reason << '\n';
  }
}

// One scene on the derived unit: its error printed, and as JSON. A hardware specular unit gets
// the exact-pow yardstick on the same widths: what of the error is the unit's own. A scene over
// the budget adds why to `missed`, and its cause (verified by re-shading the frame with it
// removed, or "unknown": derive/miss_causes.h) to the JSON. `cycles`: what the derivation
// measured on the unit, as `cycles` counts them (scripts/random-scenes compares the two).
nlohmann::json check_scene(const PreparedScene& frame, const DerivedConfig& derived,
                           const SceneCycles& cycles, std::vector<std::string>& missed) {
  const std::string& path = frame.path();
  const UnitConfig& cfg = derived.config;
  const double budget = derived.measured.budget_lsb;
  const ErrorStats e = scene_error(frame, cfg);
  if (e.pixels == 0) {
    // As render: an image with no pixel has no error and no PSNR to report.
    std::cout << "  " << path
              << ": the image is empty (no pixel covered): no error or PSNR to report\n";
  } else {
    std::cout << "  " << path << ": max " << e.max_code_lsb << " LSB, mean " << std::setprecision(4)
              << e.mean_code_lsb << " LSB, PSNR "
              << (std::isinf(e.psnr_db) ? std::string("inf")
                                        : std::to_string(e.psnr_db).substr(0, 5) + " dB")
              << ", max real " << std::setprecision(3) << e.max_real_lsb << " LSB, "
              << e.pixels_over_1lsb << " of " << e.pixels << " pixels off by more than 1\n";
  }
  nlohmann::json yardstick = nullptr;
  std::optional<ErrorStats> with_ideal;
  if (specular_unit(cfg.specular.kind).hardware) {
    UnitConfig ideal = cfg;
    ideal.specular.kind = SpecularUnitKind::kIdeal;
    const ErrorStats y = scene_error(frame, ideal);
    with_ideal = y;
    std::cout << "    with ideal (exact pow, not hardware) on the same widths: max "
              << y.max_code_lsb << " LSB, max real " << std::setprecision(3) << y.max_real_lsb
              << " LSB\n";
    if (y.max_code_lsb < e.max_code_lsb) {
      std::cout << "    the difference is the " << to_string(cfg.specular.kind)
                << " unit's own approximation of t^n, not the widths' (see shadesim spec-error, "
                   "--fit)\n";
    }
    yardstick = {{"max_code_lsb", y.max_code_lsb}, {"max_real_lsb", y.max_real_lsb}};
  }
  nlohmann::json cause = nullptr;
  if (e.max_code_lsb > code_budget(budget)) {
    const MissExplanation why = explain_miss_cause(frame, cfg, e);
    missed.push_back(path + ": " + why.text);
    cause = {{"cause", to_string(why.cause)},
             {"verified", why.verified()},
             {"max_code_lsb_without", why.error_removed}};
  }
  return {{"scene", path},
          {"miss_cause", cause},
          {"cycles_per_pixel", cycles.per_pixel()},
          {"cycles", cycles.cycles},
          {"with_ideal_specular", yardstick},
          {"within_budget", e.max_code_lsb <= code_budget(budget)},
          {"pixels", e.pixels},
          {"max_code_lsb", e.max_code_lsb},
          {"mean_code_lsb", e.mean_code_lsb},
          {"psnr_db", std::isinf(e.psnr_db) || e.pixels == 0 ? nlohmann::json(nullptr)
                                                             : nlohmann::json(e.psnr_db)},
          {"max_real_lsb", e.max_real_lsb},
          {"pixels_over_1lsb", e.pixels_over_1lsb}};
}

// The UnitConfig's own fields (load_unit_config and --config read them), and beside them the
// "derivation" annotation, which the loader ignores.
nlohmann::json config_json(const ConfigOptions& o, const DerivedConfig& derived,
                           const nlohmann::json& scenes, const std::vector<std::string>& missed) {
  nlohmann::json j = nlohmann::json::parse(config_to_json(derived.config));
  nlohmann::json reasons = nlohmann::json::array();
  for (const auto& r : derived.reasons)
    reasons.push_back({{"field", r.field}, {"value", r.value}, {"reason", r.reason}});
  const ConfigMeasurements& m = derived.measured;
  j["derivation"] = {{"scenes", o.scenes},
                     {"reasons", reasons},
                     {"measured",
                      {{"budget_lsb", m.budget_lsb},
                       {"max_width", m.max_width},
                       {"max_height", m.max_height},
                       {"longest_span", m.longest_span},
                       {"max_offset", m.max_offset},
                       {"max_monomial_sum", m.max_monomial_sum},
                       {"series_min", m.series_min},
                       {"series_max", m.series_max},
                       {"difference_max", m.difference_max},
                       {"coef_max", m.coef_max},
                       {"gain", m.gain},
                       {"drift_share_lsb", m.drift_share_lsb},
                       {"coef_share_lsb", m.coef_share_lsb}}},
                     {"error_misses", missed},
                     {"cycles_misses", derived.cycles_misses},
                     {"error", scenes}};
  return j;
}

// What --clock-mhz found: each unit timed, the one chosen, and why none meets it if so.
nlohmann::json clock_json(const ClockTarget& target, const ClockOutcome& c) {
  nlohmann::json tried = nlohmann::json::array();
  for (const ClockTiming& t : c.tried) {
    tried.push_back({{"combine_stages", t.unit.combine_stages},
                     {"square_stages", pipelining_of(t.unit).square_stages},
                     {"fmax_mhz", t.fmax_mhz ? nlohmann::json(*t.fmax_mhz) : nlohmann::json()},
                     {target.site == ClockSite::kIce40 ? "lut4" : "area_um2", t.area},
                     {"limit", t.limit}});
  }
  return {{"target_mhz", target.mhz},
          {"required_fmax_mhz", required_mhz(target)},
          {"site", site_name(target)},
          {"tried", tried},
          {"chosen", c.chosen},
          {"meets", c.meets},
          {"miss", c.miss}};
}

// The scenes the unit runs over the cycles target (DerivedConfig::cycles_misses, each naming
// the resource that limits it), on stderr; whether there is one.
bool report_cycles_misses(const DerivedConfig& derived) {
  if (derived.cycles_misses.empty()) return false;
  std::cerr << "shadesim config: the unit misses the cycles target on "
            << derived.cycles_misses.size() << " scene(s):\n";
  for (const auto& m : derived.cycles_misses) std::cerr << "  " << m << '\n';
  return true;
}

}  // namespace

int run_config(const ConfigOptions& o) {
  const DeriveOptions d = derive_options(o);
  check_derive_options(o.scenes, d);
  // Each scene is prepared once: the derivation's candidates (on a cache miss), the clock's
  // rungs and the error checks below all re-encode and re-shade the same frames.
  PreparedScenes prepared;
  const FrameSet frames(prepared, o.scenes, prepare_key(d));
  const CachedDerivation cached = cached_derive_config(frames, d, default_unit_cache_dir());
  DerivedConfig derived = cached.derived;
  std::optional<ClockOutcome> clock;
  ClockTarget target;
  target.site = parse_clock_site(o.clock_target, "--clock-target");
  target.mhz = o.clock_mhz < 0 ? default_clock_mhz(target.site) : o.clock_mhz;
  if (target.mhz > 0) {
    target.liberty = o.liberty;
    target.cache_dir = o.area_cache;
    const std::string before = config_to_json(derived.config);
    clock = meet_clock(frames, d, target, derived);
    // A pipelined unit's cycles are not those the derivation measured on the unpipelined one.
    if (config_to_json(derived.config) != before) derived.cycles.clear();
  }
  print_derivation(derived, cached.origin());
  std::cout << "\nerror on this unit (8-bit codes vs the reference rounded by the same rule; real "
               "= before "
               "rounding the reference)\n";
  nlohmann::json scenes = nlohmann::json::array();
  std::vector<std::string> missed;
  for (size_t i = 0; i < frames.size(); ++i) {
    const SceneCycles cycles = derived.cycles.size() == frames.size()
                                   ? derived.cycles[i]
                                   : scene_cycles(frames.at(i), derived.config);
    scenes.push_back(check_scene(frames.at(i), derived, cycles, missed));
  }
  if (!o.json_path.empty()) {
    nlohmann::json j = config_json(o, derived, scenes, missed);
    if (clock) j["derivation"]["clock"] = clock_json(target, *clock);
    write_text_file(o.json_path, j.dump(2) + '\n');
    std::cout << "\nconfig       " << o.json_path << " (use with --config)\n";
  }
  if (!missed.empty()) {
    std::cerr << "shadesim config: the unit misses the budget on " << missed.size()
              << " scene(s):\n";
    for (const auto& m : missed) std::cerr << "  " << m << '\n';
  }
  const bool cycles_missed = report_cycles_misses(derived);
  if (clock && !clock->meets) std::cerr << "shadesim config: " << clock->miss << '\n';
  return missed.empty() && !cycles_missed && (!clock || clock->meets) ? 0 : 1;
}

}  // namespace shadesim
