#include "derive/specular_search.h"

#include <algorithm>
#include <optional>
#include <stdexcept>

#include "derive/budget.h"
#include "derive/format_widening.h"
#include "derive/helpers.h"
#include "derive/specular_candidates.h"
#include "derive/throughput_choice.h"
#include "host/parallel.h"
#include "host/scene_error.h"

namespace shadesim {
namespace {

// A specular term: a non-zero specular colour under a light of non-zero colour in some channel.
// Without one in any scene the unit needs no specular unit.
bool has_specular_term(const std::vector<SceneInfo>& scenes) {
  for (const auto& s : scenes) {
    for (const auto& m : s.scene.materials) {
      for (const auto& light : s.scene.lights) {
        for (int c = 0; c < 3; ++c) {
          if (channel(m.specular, c) * channel(light.colour, c) != 0) return true;
        }
      }
    }
  }
  return false;
}

// The specular unit the materials name. One unit serves every scene, so where it matters (some
// scene has a specular term) every material must name the same one.
SpecularUnitKind named_unit(const std::vector<SceneInfo>& scenes, bool specular) {
  const SceneInfo& unit_scene = scenes.front();
  const Material& unit_material = unit_scene.scene.materials.front();
  if (!specular) return unit_material.unit;
  for (const auto& s : scenes) {
    for (const auto& m : s.scene.materials) {
      if (m.unit != unit_material.unit) {
        throw std::invalid_argument(
            "derive_config: one unit serves every scene, but " + unit_scene.path + " (material '" +
            unit_material.name + "') names the specular unit " + to_string(unit_material.unit) +
            " and " + s.path + " (material '" + m.name + "') names " + to_string(m.unit) +
            "; derive them separately or make the materials agree");
      }
    }
  }
  return unit_material.unit;
}

// The largest error of `config` over the scenes, in output codes.
int max_code_error(const FrameSet& frames, const UnitConfig& config) {
  int worst = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    worst = std::max(worst, scene_error(frames.at(i), config).max_code_lsb);
  }
  return worst;
}

bool substituted(const DerivedConfig& d, const DeriveOptions& options) {
  return d.substitute && d.config.specular.kind == options.ideal_substitute.kind;
}

// The units tried after the first: the ideal stand-ins, or the named kind's other fields.
std::vector<SpecularConfig> units_to_try(const DerivedConfig& first, const DeriveOptions& options) {
  if (options.specular_trial) return {};  // a search of its own is under way
  if (substituted(first, options)) return options.ideal_fallbacks;
  if (!options.search_named_units || first.substitute) return {};
  std::vector<SpecularConfig> rest = named_unit_candidates(first.config.specular.kind);
  if (!rest.empty()) rest.erase(rest.begin());  // the defaults: the first unit derived
  return rest;
}

// One unit tried: its derivation, its error and its cycles on the scenes (the worst of each).
struct UnitTrial {
  DerivedConfig derived;
  int error = 0;
  SceneCycles cycles;
  std::string describe() const {
    return derived.config.specular.describe() + " " + std::to_string(error) + " LSB at " +
           fmt(cycles.per_pixel()) + " cycles/px";
  }
};

UnitTrial try_unit(const FrameSet& frames, const DeriveOptions& options, DerivedConfig derived) {
  UnitTrial t;
  t.error = max_code_error(frames, derived.config);
  for (size_t i = 0; i < frames.size(); ++i) {
    const SceneCycles c = derived.cycles.size() == frames.size()
                              ? derived.cycles[i]
                              : scene_cycles(frames.at(i), derived.config);
    if (c.per_pixel() >= t.cycles.per_pixel()) t.cycles = c;
  }
  t.derived = std::move(derived);
  return t;
}

bool exact_pow_misses(const FrameSet& frames, const DeriveOptions& options, const UnitConfig& unit,
                      int allowed) {
  UnitConfig exact = unit;
  exact.specular.kind = SpecularUnitKind::kIdeal;
  return max_code_error(frames, exact) > allowed;
}

// Budget first: a unit within the budget is taken unless it costs more cycles than the target
// and the first unit's plus 1 % (and 2 cycles of pipeline fill per frame, which decide a frame
// of a few pixels). When none within the budget stays within that, the first within the budget
// is taken all the same and the cycles it trades are stated.
double cycles_allowance(const DeriveOptions& options, const SceneCycles& first) {
  const double pixels = std::max<double>(1.0, static_cast<double>(first.pixels));
  return std::max(cycles_target(options, first), first.per_pixel() * 1.01 + 2.0 / pixels);
}

// Tries `units` in order; `best` (the first unit, over the budget) becomes the unit taken. Returns
// the note on the specular line: what was tried, what was taken and what it traded.
std::string search_units(const FrameSet& frames, const DeriveOptions& options,
                         const DeriveUnit& derive_unit, const std::vector<SpecularConfig>& units,
                         int allowed, UnitTrial& best, std::string& tried) {
  const UnitTrial first = best;
  const double allowance = cycles_allowance(options, first.cycles);
  std::optional<UnitTrial> within, slow;
  UnitTrial closest = first, last = first;
  // Candidates are tried a batch at a time, one per thread, and read in order: the one taken and
  // the text are those of a one-by-one search whatever the thread count.
  const size_t batch = static_cast<size_t>(thread_count(options.threads));
  std::vector<UnitTrial> trials;
  for (size_t i = 0; i < units.size() && !within; ++i) {
    if (i % batch == 0) {
      const size_t n = std::min(batch, units.size() - i);
      trials = parallel_map<UnitTrial>(n, options.threads, [&](size_t k) {
        DeriveOptions o = options;
        o.specular_trial = units[i + k];
        if (first.derived.substitute) o.ideal_substitute = units[i + k];
        return try_unit(frames, o, derive_unit(o));
      });
    }
    UnitTrial& t = trials[i % batch];
    tried += ", " + t.describe();
    if (t.error < closest.error) closest = t;
    if (t.derived.config.specular.kind == closest.derived.config.specular.kind) last = t;
    if (t.error > allowed) continue;
    if (t.cycles.per_pixel() <= allowance) {
      within = std::move(t);
      continue;
    }
    tried += " (over " + fmt(allowance) + ")";
    if (!slow) slow = std::move(t);
  }
  const std::string budget = std::to_string(allowed) + " LSB";
  if (within) {
    best = *within;
    return "measured against the budget on the scenes, smallest first: " + tried +
           " (the first within " + budget + " and " + fmt(allowance) + " cycles/px)";
  }
  if (slow) {
    best = *slow;
    return "measured against the budget on the scenes, smallest first: " + tried +
           "; budget first: " + slow->derived.config.specular.describe() + " is within " + budget +
           " and trades " + fmt(slow->cycles.per_pixel() - first.cycles.per_pixel()) +
           " cycles/px against the first";
  }
  best = closest;
  return "no unit tried meets the " + budget + " budget on the scenes: " + tried +
         "; the closest, " + closest.derived.config.specular.describe() + " at " +
         std::to_string(closest.error) + " LSB, is kept. What limits it is the " +
         to_string(closest.derived.config.specular.kind) +
         " unit's function, not the formats (exact pow on the first unit's formats is within " +
         budget + "): its widest fields tried, " + last.derived.config.specular.describe() +
         ", reach " + std::to_string(last.error) + " LSB";
}

// Exact pow misses on the first unit's formats and meets the budget with `widen`: the unit
// derived again on the widened formats, then, where it still misses, the units searched on them.
std::string search_widened(const FrameSet& frames, const DeriveOptions& options,
                           const DeriveUnit& derive_unit, const std::vector<SpecularConfig>& units,
                           int allowed, const FormatWidening& widen, UnitTrial& best,
                           std::string& tried) {
  const std::string first_tried = tried;
  DeriveOptions wide = options;
  wide.widen = widen;
  best = try_unit(frames, wide, derive_unit(wide));
  tried = best.describe();
  const std::string head = "on the rules' formats " + first_tried + ", and exact pow misses too (" +
                           std::to_string(widen.exact_before) + " LSB); with " + widen.describe() +
                           " exact pow meets it (" + std::to_string(widen.exact_after) +
                           " LSB, measured), so the formats are widened and the units tried "
                           "again on them: ";
  if (best.error <= allowed) return head + tried + " (within " + std::to_string(allowed) + " LSB)";
  if (units.empty()) return head + tried + " (no other unit to try)";
  return head + search_units(frames, wide, derive_unit, units, allowed, best, tried);
}

// A unit with no other specular unit to try (none, ideal kept, a named unit not searched): its
// formats widened where they hold the scenes back (kWideningRule), else `first` as it is.
DerivedConfig widened_where_held(const FrameSet& frames, const DeriveOptions& options,
                                 const DeriveUnit& derive_unit, DerivedConfig first) {
  if (options.specular_trial) return first;
  const int allowed = code_budget(first.measured.budget_lsb);
  if (max_code_error(frames, first.config) <= allowed) return first;
  const auto widen = widening_that_holds(frames, first.config, allowed);
  if (!widen) return first;
  DeriveOptions wide = options;
  wide.widen = *widen;
  return derive_unit(wide);
}

}  // namespace

const DerivationRule kWideningRule = {
    "spec_colour, specular out, series, coef",
    "where the specular unit misses the budget on the scenes and so does exact pow on its "
    "formats, but exact pow on formats that lose nothing meets it (measured), the formats hold "
    "the scenes back: the one format that alone meets it with the fewest more fraction bits "
    "(spec_colour, then the specular output, then series and coef; else all three by the same "
    "bits), measured by re-shading the scenes, is widened, and the specular unit is derived and "
    "searched again on the widened formats"};

const DerivationRule kSpecularRule = {
    "specular",
    "none (no specular unit, no specular series) when no material has a specular term (specular "
    "colour x light colour 0 in every channel); else the unit the materials name (all must name "
    "one); `ideal` is not hardware (its RTL slot outputs 0), so it becomes W_16 B=16 pipelined, "
    "or where that misses the budget on the scenes (measured: max code error <= budget), the "
    "first that meets it of W_16 with zeta fitted, W_32 (plain, fitted) and interpolating LUTs "
    "(--ideal-unit to choose); a named lut, schlick or wpow unit whose defaults miss gets the "
    "first of its kind's fields that meets it (LUT entries, entry bits, interpolation, shared or "
    "per-exponent; Schlick's fitted n' and divider widths; W_m's squarings, base bits, fitted "
    "zeta). Budget first: the first within the budget whose cycles stay within max(target, the "
    "first unit's + 1 %), else the first within the budget all the same (its cycles stated), "
    "else the closest, with what limits it named. The reason lists each unit tried with its "
    "error and cycles"};

SpecularChoice choose_specular_unit(const std::vector<SceneInfo>& scenes,
                                    const DeriveOptions& options, UnitConfig& cfg) {
  const bool specular = has_specular_term(scenes);
  const SpecularUnitKind named = named_unit(scenes, specular);
  SpecularChoice choice;
  if (!specular) {
    cfg.specular.kind = SpecularUnitKind::kNone;
    choice.why =
        std::string(scenes.size() == 1 ? "the scene has no" : "no scene has a") +
        " specular term (every material's specular colour times every light's colour "
        "is 0): no specular unit and no specular series" +
        (named == SpecularUnitKind::kNone ? ""
                                          : " (the materials name " + to_string(named) +
                                                ", which adds 0 without a specular colour)");
  } else if (named == SpecularUnitKind::kIdeal) {
    cfg.specular = options.ideal_substitute;
    choice.substitute = cfg.specular.kind != SpecularUnitKind::kIdeal;
    choice.why = cfg.specular.kind == SpecularUnitKind::kIdeal
                     ? "the scenes name ideal, kept as asked: exact pow, not hardware (its RTL "
                       "slot outputs 0)"
                     : "the scenes name ideal, which is not hardware (its RTL slot outputs 0); "
                       "substituted by " +
                           cfg.specular.describe();
  } else {
    cfg.specular.kind = named;
    choice.why = "the unit the scenes' materials name, default widths";
  }
  if (options.specular_trial) {
    cfg.specular = *options.specular_trial;
    if (named != SpecularUnitKind::kIdeal)
      choice.why = "the unit the scenes' materials name, with the fields searched below";
  }
  cfg.specular.validate();
  return choice;
}

DerivedConfig search_specular_unit(const FrameSet& frames, const DeriveOptions& options,
                                   const DeriveUnit& derive_unit) {
  DerivedConfig first = derive_unit(options);
  const std::vector<SpecularConfig> rest = units_to_try(first, options);
  if (rest.empty() && !substituted(first, options))
    return widened_where_held(frames, options, derive_unit, first);
  // The specular unit must meet the budget on the scenes (measured, not bounded: a unit's
  // approximation of t^n is not in the width rules), else the next candidate, each with the
  // widths derived for it. The reason lists every unit tried.
  const int allowed = code_budget(first.measured.budget_lsb);
  UnitTrial best = try_unit(frames, options, first);
  std::string tried = best.describe();
  std::string note;
  if (best.error <= allowed) {
    note = "measured against the budget on the scenes: " + tried + " (within " +
           std::to_string(allowed) + " LSB)";
  } else if (!exact_pow_misses(frames, options, first.config, allowed)) {
    note = search_units(frames, options, derive_unit, rest, allowed, best, tried);
  } else if (const auto widen = options.specular_trial
                                    ? std::nullopt
                                    : widening_that_holds(frames, first.config, allowed)) {
    note = search_widened(frames, options, derive_unit, rest, allowed, *widen, best, tried);
  } else {
    // No unit and no widening will meet it: the Taylor setup or the N.L gate do not, or the
    // cause is unknown (shadesim config says which, measured, and exits 1).
    note = "misses the " + fmt(first.measured.budget_lsb) + " LSB budget on the scenes (" + tried +
           "), and so does exact pow on its formats and on formats that lose nothing: no other "
           "unit is tried";
  }
  for (auto& r : best.derived.reasons) {
    if (r.field == "specular") r.reason += "; " + note;
  }
  return best.derived;
}

}  // namespace shadesim
