// shadesim config SCENE...: derive the smallest unit that shades the scenes within the error
// budget (host/scene_config.h), print each field with how it was derived, and the error the
// bit-accurate model reaches on each scene with it.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "host/frame.h"
#include "host/metrics.h"
#include "host/reference.h"
#include "host/scene_config.h"
#include "host/scene_error.h"
#include "model/command_stream.h"
#include "model/shade_unit.h"
#include "model/specular_units.h"
#include "model/text_file.h"
#include "sim/cli/commands.h"
#include "sim/cli/number_checks.h"
#include "sim/cli/output_paths.h"

namespace shadesim {
namespace {

struct ConfigOptions {
  std::vector<std::string> scenes;
  double budget_lsb = std::nan("");
  int out_bits = 8;
  int port_words = 4;
  int tri_queue = 2;
  std::string ideal_unit;      // empty: W_16, then the fallbacks that meet the budget
  std::string span_setup;      // empty: derived
  std::string diffuse_colour;  // empty: derived
  double max_cycles_per_pixel = 1.10;
  std::string json_path;
};

// The scene on exactly `config`, through the model and the reference, with render's metrics.
ErrorStats shade(const std::string& path, const UnitConfig& config, const DeriveOptions& d) {
  return scene_error(path, config, d.budget_lsb, d.max_depth);
}

// Why a scene misses the budget: the specular unit's function when exact pow on the same widths
// meets it, else the widths, the Taylor setup or the N.L gate (exact pow misses it too).
std::string missed_budget_part(const std::string& path, const ErrorStats& e,
                               const std::optional<ErrorStats>& ideal, double budget) {
  std::ostringstream os;
  os << path << ": max " << e.max_code_lsb << " LSB, " << e.max_code_lsb - code_budget(budget)
     << " LSB over the " << budget << " LSB budget (" << code_budget(budget)
     << " in output codes): ";
  if (ideal && ideal->max_code_lsb <= code_budget(budget)) {
    os << "the specular unit's own approximation of t^n (exact pow on the same widths: "
       << ideal->max_code_lsb << " LSB); try another unit or its fields (shadesim spec-error)";
  } else {
    os << "the widths, the Taylor setup or the N.L gate, not the specular unit"
       << (ideal
               ? " (exact pow on the same widths: " + std::to_string(ideal->max_code_lsb) + " LSB)"
               : std::string())
       << "; a lower --budget narrows the setup and widens the series";
  }
  return os.str();
}

DeriveOptions derive_options(const ConfigOptions& o) {
  DeriveOptions d;
  if (!std::isnan(o.budget_lsb)) d.budget_lsb = o.budget_lsb;
  d.out_bits = o.out_bits;
  d.port_words = o.port_words;
  d.tri_queue = o.tri_queue;
  d.max_cycles_per_pixel = o.max_cycles_per_pixel;
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

// The unit, and each field with how it was derived.
void print_derivation(const DerivedConfig& derived) {
  std::cout << "unit         " << derived.config.to_string() << "\n\n";
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
// the budget adds why to `missed`.
nlohmann::json check_scene(const std::string& path, const DerivedConfig& derived,
                           const DeriveOptions& d, std::vector<std::string>& missed) {
  const UnitConfig& cfg = derived.config;
  const double budget = derived.measured.budget_lsb;
  const ErrorStats e = shade(path, cfg, d);
  std::cout << "  " << path << ": max " << e.max_code_lsb << " LSB, mean " << std::setprecision(4)
            << e.mean_code_lsb << " LSB, PSNR "
            << (std::isinf(e.psnr_db) ? std::string("inf")
                                      : std::to_string(e.psnr_db).substr(0, 5) + " dB")
            << ", max real " << std::setprecision(3) << e.max_real_lsb << " LSB, "
            << e.pixels_over_1lsb << " of " << e.pixels << " pixels off by more than 1\n";
  nlohmann::json yardstick = nullptr;
  std::optional<ErrorStats> with_ideal;
  if (specular_unit(cfg.specular.kind).hardware) {
    UnitConfig ideal = cfg;
    ideal.specular.kind = SpecularUnitKind::kIdeal;
    const ErrorStats y = shade(path, ideal, d);
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
  if (e.max_code_lsb > code_budget(budget))
    missed.push_back(missed_budget_part(path, e, with_ideal, budget));
  return {{"scene", path},
          {"with_ideal_specular", yardstick},
          {"within_budget", e.max_code_lsb <= code_budget(budget)},
          {"pixels", e.pixels},
          {"max_code_lsb", e.max_code_lsb},
          {"mean_code_lsb", e.mean_code_lsb},
          {"psnr_db", std::isinf(e.psnr_db) ? nlohmann::json(nullptr) : nlohmann::json(e.psnr_db)},
          {"max_real_lsb", e.max_real_lsb},
          {"pixels_over_1lsb", e.pixels_over_1lsb}};
}

// The UnitConfig's own fields (load_unit_config and --config read them), and beside them the
// "derivation" annotation, which the loader ignores.
nlohmann::json config_json(const ConfigOptions& o, const DerivedConfig& derived,
                           const nlohmann::json& scenes) {
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
                     {"error", scenes}};
  return j;
}

int run_config(const ConfigOptions& o) {
  const DeriveOptions d = derive_options(o);
  const DerivedConfig derived = derive_config(o.scenes, d);
  print_derivation(derived);
  std::cout << "\nerror on this unit (8-bit codes vs the reference rounded by the same rule; real "
               "= before "
               "rounding the reference)\n";
  nlohmann::json scenes = nlohmann::json::array();
  std::vector<std::string> missed;
  for (const auto& path : o.scenes) scenes.push_back(check_scene(path, derived, d, missed));
  if (!o.json_path.empty()) {
    write_text_file(o.json_path, config_json(o, derived, scenes).dump(2) + '\n');
    std::cout << "\nconfig       " << o.json_path << " (use with --config)\n";
  }
  if (!missed.empty()) {
    std::cerr << "shadesim config: the unit misses the budget on " << missed.size()
              << " scene(s):\n";
    for (const auto& m : missed) std::cerr << "  " << m << '\n';
    return 1;
  }
  return 0;
}

}  // namespace

void register_config(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ConfigOptions>();
  CLI::App* sub = app.add_subcommand(
      "config",
      "Derive the smallest unit that shades the scene(s) within the error budget, print every "
      "field\n"
      "with how it was derived (with the measured numbers), and the error the bit-accurate model\n"
      "reaches on each scene with it. --json writes a UnitConfig file for --config.\n"
      "Rules:\n"
      "  channels     1 if every scene is grey, else 3\n"
      "  lights       the most directional lights of any scene\n"
      "  specular     none (no specular unit, no specular series) when no material has a\n"
      "               specular term (specular colour x light colour 0 in every channel); else\n"
      "               the unit the materials name (all must name one); `ideal` is not hardware\n"
      "               (its RTL slot outputs 0), so it becomes W_16 B=16 pipelined, or where\n"
      "               that misses the budget on the scenes (measured), the first of W_32 B=16,\n"
      "               LUT A=10 B=12 F=4, LUT A=10 B=16 F=6 that meets it; the reason lists each\n"
      "               unit tried with its error\n"
      "  xy_bits      enough unsigned bits for the largest image width and height (at least 4)\n"
      "  offset_bits  enough signed bits for the largest |dx|, |dy| of a span's first pixel from\n"
      "               its triangle's origin, so no triangle is re-origined\n"
      "  series       integer bits: the fewest (>= 2) holding every series value at every pixel\n"
      "               (measured on a trial unit that loses nothing); fraction bits F: the proven\n"
      "               drift bound over the longest span L, 2^-F (1 + L(L-1)/2) (half with "
      "rounding),\n"
      "               times the gain G of the series into one output channel, <= budget/4 LSB\n"
      "  coef         integer bits: wrapping, the series' (exact modulo 2^iwl: span setup "
      "multiplies\n"
      "               coefficients only by integers); fraction bits: coefficient rounding "
      "2^-(F+1)\n"
      "               times the largest 1+|dx|+|dy|+dx^2+|dx dy|+dy^2 of a pixel from its "
      "triangle's\n"
      "               origin, times G, <= budget/4 LSB\n"
      "  coef_term_iwl  coefficient packing: T0 keeps coef's integer bits (it wraps); T1..T5 the\n"
      "               fewest saturating integer bits holding every measured |T_t| + 1 LSB\n"
      "  out_bits     as requested (--out-bits)\n"
      "  port_words, tri_queue  as requested (--port-words 4, --tri-queue 2 by default)\n"
      "  span_setup   host (the host sends each span's start values: no span setup, no\n"
      "               coefficient banks, tri_queue 1) where every scene stays <= 1.10 cycles per\n"
      "               pixel with it by the cycle model (--max-cycles-per-pixel), else unit\n"
      "               (--span-setup to choose)\n"
      "  diffuse_colour  multiply with 3 channels (one N.L series per light, times kd_c L_c per\n"
      "               pixel and channel), series with 1 (--diffuse-colour to choose)\n"
      "  spec_colour, specular widths: defaults\n"
      "  G = sum over lights of (1, or max kd_c L_c multiplied, + max specular colour x the\n"
      "  unit's slope on its series), the\n"
      "  slope from t^n's <= n on [0, 1] through setup's pre-scaling. The Taylor error keeps the\n"
      "  whole budget in setup; the fixed-point error adds at most half of it.\n"
      "Exits 1 when the unit misses the budget on a scene (measured), saying which part: the\n"
      "specular unit's function, or the widths, Taylor setup or N.L gate.");
  sub->add_option("scenes", o->scenes, "scene JSON files")->required()->check(CLI::ExistingFile);
  sub->add_option(
         "--budget", o->budget_lsb,
         "error budget in output LSBs (default: the smallest error_budget_lsb of the scenes)")
      ->check(positive_number());
  sub->add_option("--out-bits", o->out_bits, "output bits per channel")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  sub->add_option("--port-words", o->port_words,
                  "command port width of the unit (64-bit words per handshake; throughput only)")
      ->check(CLI::IsMember({1, 2, 4, 8}))
      ->capture_default_str();
  sub->add_option("--tri-queue", o->tri_queue, "triangle queue depth of the unit (throughput only)")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  sub->add_option("--span-setup", o->span_setup,
                  "span setup in the unit or on the host (default: derived, see above)")
      ->check(CLI::IsMember({"unit", "host"}));
  sub->add_option(
         "--diffuse-colour", o->diffuse_colour,
         "diffuse colour rolled into the series or multiplied per pixel (default: derived)")
      ->check(CLI::IsMember({"series", "multiply"}));
  sub->add_option("--max-cycles-per-pixel", o->max_cycles_per_pixel,
                  "the cycles/pixel host span setup may take (cycle model) for config to choose it")
      ->check(positive_number())
      ->capture_default_str();
  sub->add_option(
      "--ideal-unit", o->ideal_unit,
      "hardware unit for scenes that name ideal, and no other: wpow (W_16 B=16 pipelined),\n"
      "lut or schlick (their default widths), or ideal to keep the yardstick (no RTL); default:\n"
      "W_16, else the first of W_32 and two interpolating LUTs that meets the budget");
  sub->add_option(
         "--json", o->json_path,
         "write the UnitConfig JSON (loadable by --config) with a \"derivation\" block: reasons, "
         "measurements, errors")
      ->check(output_file());
  sub->callback([o, &exit_code]() { exit_code = run_config(*o); });
}

}  // namespace shadesim
