// The throughput structure of a unit whose widths are final: the command port's words, the span
// setup site (with the host's start bank depth, or the unit's triangle queue), the material
// buffers and, for a Schlick or W_m unit, its timing (iterative or pipelined). Pixels depend on
// none of them (model/host_setup.h; model/schlick_divider.h and model/wpow_unit.h: "same bits
// either way"; the encoder writes the same MATERIAL and TABLE words for one or two buffers), so
// they are chosen on cycles alone: by the cycle model with no gaps and no back-pressure
// (CycleEstimate, exactly the clocked model's count), on every scene.
//
// The rule (kThroughputRule: config --help's text): the cheapest candidate that runs every
// scene within its cycles target (cycles_target: DeriveOptions::max_cycles_per_pixel, or by
// default 1.10 cycles per beat of the unit's lanes). Candidates in cost order, cheapest first
// (what each knob adds, measured in docs/history/area.md):
//   1. span setup on the host before the unit (the unit's span setup, coefficient banks and span
//      queue are 12,964 + 6,782 + 3,197 GE of specular's unit with unit setup; the host's start
//      bank 5,508);
//   2. an iterative Schlick or W_m unit before a pipelined one (Q subtract stages, or log2(m)
//      squarers, instead of one);
//   3. fewer port words: 1, 2, 4, 8 (the beat, and its write steering into every bank entry);
//   4. a shallower start bank (host: start_depth 1, 2) or triangle queue (unit: tri_queue 1..8);
//   5. one material buffer before two (two banks of the per-material registers, and of a LUT's
//      table RAM).
// Lexicographic: no area model weighs a port word against a bank entry (a wider port adds write
// steering into every entry; docs/history/area.md has no measurement of either alone), so the order
// is the stated convention, and every knob's reason gives the figure of the step cheaper in it. A
// knob given in DeriveOptions (port_words, tri_queue, span_setup) is held at its value. Lanes stay
// as the unit has them (derive_config sets DeriveOptions::lanes); with more lanes the port and
// the start bank or triangle queue must bring a span's words in fewer cycles, and the same
// candidates cover it (sphere_1024 at 4 lanes needs a 4-word port and start_depth 2). Where no
// candidate meets the target: the fastest (the lowest worst cycles per pixel over the scenes,
// each relative to its target; of those within kFastestTolerance of it, the cheapest), and every
// scene over its target is named with the resource that limits it (cycles_miss).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "derive/cycles_limit.h"
#include "derive/derive_config.h"
#include "model/command_stream.h"
#include "model/cycle_estimate.h"
#include "model/unit_config.h"

namespace shadesim {

// Where nothing meets the target, candidates this close to the fastest (relative, in worst
// cycles per pixel) count as fast as it, so a cycle or two on a tiny frame buys no hardware.
constexpr double kFastestTolerance = 0.01;

// The default cycles target, per beat: a beat is the up to `lanes` pixels of one span that leave
// the unit together (a span of len pixels takes ceil(len / lanes) beats; lanes stay within a
// span). With one lane a beat is a pixel, and this is 1.10 cycles per pixel.
constexpr double kMaxCyclesPerBeat = 1.10;

// A frame's cycles target in cycles per pixel: DeriveOptions::max_cycles_per_pixel where given,
// else kMaxCyclesPerBeat x its beats / pixels on the unit's lanes (`frame`: its beats, pixels).
// Not kMaxCyclesPerBeat / lanes: a frame's beats / pixels is the least any structure reaches, and
// above 1 / lanes wherever a span's length is no multiple of the lanes (sphere_1024 on 4 lanes:
// 230,466 beats for 759,144 pixels, 0.304 cycles/px at best, over 1.10 / 4 = 0.275).
double cycles_target(const DeriveOptions& options, const SceneCycles& frame);

// One candidate's knobs.
struct ThroughputKnobs {
  SpanSetupSite span_setup = SpanSetupSite::kHost;
  bool pipelined = false;  // the specular unit's timing (Schlick and W_m only; else as it is)
  int material_buffers = 1;
  int port_words = 1;
  int depth = 1;  // host: start_depth; unit: tri_queue

  // `unit` with these knobs (tri_queue 1 with host setup; start_depth as it is with unit setup).
  UnitConfig applied_to(const UnitConfig& unit) const;
  // E.g. "host setup, P=4, start_depth 2, 1 material buffer".
  std::string to_string(const UnitConfig& unit) const;
};

// Whether the unit's specular kind has a timing to choose (Schlick, W_m).
bool has_timing_choice(const UnitConfig& unit);

// Every candidate the options allow for `unit`, cheapest first (the cost order above). Throws
// std::invalid_argument where the requests leave none (span_setup host with tri_queue > 1).
std::vector<ThroughputKnobs> throughput_candidates(const UnitConfig& unit,
                                                   const DeriveOptions& options);

struct ThroughputChoice {
  ThroughputKnobs knobs;
  UnitConfig config;                     // the unit with `knobs`
  bool meets = false;                    // every scene within the target
  std::vector<double> cycles_per_pixel;  // per scene, on `config`
  std::vector<SceneCycles> cycles;       // per scene, on `config`
  std::vector<double> targets;           // per scene, cycles per pixel (cycles_target)
  std::vector<std::string> misses;       // cycles_miss of each scene over its target
  size_t candidates_measured = 0;
  // Why each knob has its value, with the figures of the candidate one step cheaper in it (lanes:
  // as the unit has them, with the cycles target they set).
  std::string port_words, tri_queue, start_depth, span_setup, material_buffers, timing, lanes;
};

// Chooses the knobs for `unit` (its widths final) on the scenes. Each scene is prepared once
// (unit setup; its host-setup stream is derived from it, as the encoder does) and each candidate
// re-runs only the cycle model.
ThroughputChoice choose_throughput(const FrameSet& frames, const DeriveOptions& options,
                                   const UnitConfig& unit);

// The rule above as shadesim config --help states it.
extern const DerivationRule kThroughputRule;

}  // namespace shadesim
