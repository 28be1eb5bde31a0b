#include "derive/pipelining.h"

#include <fmt/format.h>

#include <algorithm>

#include "derive/reasons.h"
#include "model/wpow_unit.h"

namespace shadesim {

std::string Pipelining::describe() const {
  std::string s = "combine_stages " + std::to_string(combine_stages);
  if (square_stages != 1) s += ", square_stages " + std::to_string(square_stages);
  return s;
}

namespace {
bool squares_pipelined(const UnitConfig& unit) {
  return unit.specular.kind == SpecularUnitKind::kWpow &&
         unit.specular.wpow.timing == UnitTiming::kPipelined &&
         WpowUnit::stages(unit.specular.wpow) > 0;
}
}  // namespace

Pipelining pipelining_of(const UnitConfig& unit) {
  return {unit.combine_stages, squares_pipelined(unit) ? unit.specular.wpow.square_stages : 1};
}

std::vector<Pipelining> pipelining_ladder(const UnitConfig& unit) {
  std::vector<Pipelining> ladder = {{0, 1}, {1, 1}, {2, 1}};
  if (squares_pipelined(unit)) ladder.push_back({2, 2});
  return ladder;
}

void pipeline_unit(const FrameSet& frames, const DeriveOptions& options, const Pipelining& p,
                   const std::string& why, DerivedConfig& derived) {
  derived.config.combine_stages = p.combine_stages;
  if (derived.config.specular.kind == SpecularUnitKind::kWpow)
    derived.config.specular.wpow.square_stages = p.square_stages;
  derived.config.validate();
  rechoose_throughput(frames, options, derived);
  derived.reasons.erase(
      std::remove_if(derived.reasons.begin(), derived.reasons.end(),
                     [](const FieldReason& r) { return r.field == "combine_stages"; }),
      derived.reasons.end());
  derived.reasons.push_back({"combine_stages", std::to_string(p.combine_stages), why});
}

const DerivationRule kPipeliningRule = {
    "combine_stages, square_stages",
    "the first rung of the pipelining ladder that meets the clock (--clock-mhz, timed by "
    "synthesis where --clock-target says): none, combine_stages 1, 2, then a pipelined W_m "
    "unit's square_stages 2; else the fastest, its limiting path named. With --clock-mhz 0: none "
    "(combine_stages 0, square_stages 1)"};

// Times each rung of the unit's pipelining ladder (pipelining_ladder) until one meets the
// clock; keeps that one (every rung adds registers, so the first that meets is the cheapest),
// else the fastest, and states every rung's figures in the "combine_stages" reason.
ClockOutcome climb_ladder(const FrameSet& frames, const DeriveOptions& options,
                          const RungTimer& timer, DerivedConfig& derived) {
  ClockOutcome out;
  const std::string& at = timer.at;
  const std::vector<Pipelining> ladder = pipelining_ladder(derived.config);
  std::vector<DerivedConfig> units;
  for (const Pipelining& p : ladder) {
    DerivedConfig piped = derived;
    if (!units.empty()) pipeline_unit(frames, options, p, "", piped);
    out.tried.push_back(timer.time(piped.config));
    units.push_back(std::move(piped));
    if (out.tried.back().meets(timer.required_mhz > 0 ? timer.required_mhz : timer.mhz)) {
      out.meets = true;
      break;
    }
  }
  out.chosen = out.tried.size() - 1;
  if (!out.meets) {
    for (size_t i = 0; i < out.tried.size(); ++i) {
      if (out.tried[i].fmax_mhz.value_or(0) > out.tried[out.chosen].fmax_mhz.value_or(0))
        out.chosen = i;
    }
  }
  const ClockTiming& plain = out.tried[0];
  const ClockTiming& chosen = out.tried[out.chosen];
  std::string why = "the clock: unpipelined " + timer.figures(plain);
  for (size_t i = 1; i < out.tried.size(); ++i) {
    why += "; " + ladder[i].describe() + " " + timer.figures(out.tried[i]);
    if (plain.area > 0)
      why += fmt::format(" ({:+.1f} % area)", 100.0 * (out.tried[i].area / plain.area - 1));
  }
  why += out.meets ? "; meets " + at : "; misses " + at;
  if (!out.meets) {
    out.miss = fmt::format("no unit meets {}: the fastest, {} ({}), is limited by its {}", at,
                           timer.figures(chosen), ladder[out.chosen].describe(), chosen.limit);
  }
  if (out.chosen == 0 && out.tried.size() == 1) {
    derived.reasons.push_back(
        {"combine_stages", "0",
         "the clock: " + timer.figures(plain) + " meets " + at + " unpipelined"});
  } else {
    pipeline_unit(frames, options, ladder[out.chosen], why, derived);
  }
  return out;
}

}  // namespace shadesim
