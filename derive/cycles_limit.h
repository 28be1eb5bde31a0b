// What limits a frame's cycles on a unit, in words a designer acts on: the largest row of the
// cycle model's breakdown other than pixels, named as the resource behind it (the port's words per
// triangle or span, table reloads, the specular unit's initiation interval, material loads, a
// frame's fixed overhead). config names it for each scene over the cycles target, and so does
// `cycles`.
#pragma once

#include <cstdint>
#include <string>

#include "model/command_stream.h"
#include "model/cycle_estimate.h"
#include "model/unit_config.h"

namespace shadesim {

// What a stream carries, for the resource a miss names; summed over chunks with +=.
struct StreamCounts {
  uint64_t triangles = 0, spans = 0, materials = 0, table_words = 0, pixels = 0;
  uint64_t beats = 0;  // pixel beats at the lanes counted for (lanes stay within a span)
  StreamCounts& operator+=(const StreamCounts& o);
};
StreamCounts count(const CommandStream& stream, int lanes);

// "P pixels in B beats of up to L (...), X cycles/px at the least": the floor lanes set.
std::string lanes_floor(const StreamCounts& n, int lanes);

// Cycles per pixel of a run (0 for a frame without pixels).
double cycles_per_pixel(const CycleEstimateRun& run);

// What limits a frame's cycles on `unit`, from the no-gap run's breakdown (`run` from
// CycleEstimate::run(words, true) on `stream`): the largest row other than pixels, named as the
// resource behind it, with its numbers. E.g. "setup-bound: 1 + 96 words per triangle on a 4-word
// port (...); command_words 41,016 of 56,120 cycles, 4.7 cycles/px".
std::string cycles_limit(const UnitConfig& unit, const CommandStream& stream,
                         const CycleEstimateRun& run);
std::string cycles_limit(const UnitConfig& unit, const StreamCounts& n,
                         const CycleEstimateRun& run);

// "" when the run is within `target` cycles per pixel; else one line naming the scene, its
// cycles per pixel, the target and cycles_limit. `config` and `cycles` both say it with this.
std::string cycles_miss(const std::string& scene, const UnitConfig& unit,
                        const CommandStream& stream, const CycleEstimateRun& run, double target);
// The same from a streamed frame's counts (a frame whose stream was never held whole).
std::string cycles_miss(const std::string& scene, const UnitConfig& unit, const StreamCounts& n,
                        const CycleEstimateRun& run, double target);

}  // namespace shadesim
