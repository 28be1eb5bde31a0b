// A unit's pipelining, the knobs a clock target turns (pixels do not depend on them), and the
// climb up its ladder: each rung timed where the unit will be built, the first that meets the
// clock kept (kPipeliningRule). The caller times a rung (sim/engines/clock_target.cpp: by
// synthesis, through shadesim area's flows), so derive/ runs no EDA tool itself.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "derive/derive_config.h"
#include "host/prepared_scene.h"
#include "model/unit_config.h"

namespace shadesim {

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

// One unit's clock where it is built.
struct ClockTiming {
  UnitConfig unit;
  std::optional<double> fmax_mhz;  // none: the unit was not timed (no fit on the HX8K)
  double area = 0;                 // um^2 in the library, LUT4s on the iCE40
  std::string limit;               // the critical path (library) or why no Fmax (iCE40)
  bool meets(double mhz) const { return fmax_mhz && *fmax_mhz >= mhz; }
};

// What the climb did, for config's report and --json.
struct ClockOutcome {
  std::vector<ClockTiming> tried;  // the derived unit, then each rung of its ladder timed
  size_t chosen = 0;               // index into `tried`: the cheapest that meets, else fastest
  bool meets = false;
  std::string miss;  // when none meets: the fastest's Fmax and the path that limits it
};

// How the climb times a rung where the unit will be built.
struct RungTimer {
  double mhz = 0;           // the clock to meet
  double required_mhz = 0;  // the Fmax a rung needs to meet it (the clock with a guard band);
                            // 0: mhz itself
  std::string at;  // "250 MHz on osu018 0.18 um (...)": the clock and the site, for the reasons
  std::function<ClockTiming(const UnitConfig& unit)> time;
  std::function<std::string(const ClockTiming& t)> figures;  // "Fmax 251.3 MHz, 51234 um^2"
};

// Times `derived.config`; where it misses the clock, climbs its pipelining ladder, timing each
// rung until one meets it. `derived` becomes the chosen unit, with a "combine_stages" reason
// stating the figures.
ClockOutcome climb_ladder(const FrameSet& frames, const DeriveOptions& options,
                          const RungTimer& timer, DerivedConfig& derived);

extern const DerivationRule kPipeliningRule;

}  // namespace shadesim
