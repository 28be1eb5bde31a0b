#include "derive/cycles_limit.h"

#include <algorithm>
#include <stdexcept>
#include <variant>
#include <vector>

#include "derive/helpers.h"
#include "model/coef_packing.h"
#include "model/cycle_model.h"
#include "model/start_packing.h"

namespace shadesim {
namespace {

// The resource behind a breakdown row, in words a designer acts on.
std::string resource(const std::string& row, const UnitConfig& unit, const StreamCounts& n,
                     const CycleEstimateRun& run) {
  const std::string port = (unit.port_words == 8 ? "an " : "a ") + std::to_string(unit.port_words) +
                           "-word port" + (unit.port_words == 8 ? " (the widest)" : "");
  const double per_span =
      n.spans ? static_cast<double>(n.pixels) / static_cast<double>(n.spans) : 0;
  if (row == "command_words" && unit.host_setup()) {
    return "setup-bound: 1 + " + std::to_string(StartLayout::of(unit).words) +
           " words per span (host span setup's start values) on " + port + ", " + grouped(n.spans) +
           " spans of " + fixed(per_span, 1) + " px on average";
  }
  if (row == "command_words") {
    size_t bound = 0;
    for (const TriangleCost& t : run.triangles) bound += t.setup_bound();
    return "setup-bound: 1 + " + std::to_string(CoefLayout::of(unit).words) +
           " payload words per triangle on " + port + ", " + grouped(bound) + " of " +
           grouped(run.triangles.size()) + " triangles with more decoder than engine cycles";
  }
  if (row == "table") {
    return "table reload: " + grouped(n.table_words) + " TABLE words, one entry a cycle, for " +
           grouped(n.pixels) + " pixels";
  }
  if (row == "unit_stall") {
    return "the specular unit's initiation interval: " + unit.specular.describe() + " takes " +
           std::to_string(SlotTiming::of(unit.specular).interval) + " cycles per pixel";
  }
  if (row == "material") {
    return "material loads: " + grouped(n.materials) +
           " MATERIAL commands, each waiting for the datapath (" +
           std::to_string(unit.material_buffers) + " material buffer(s))";
  }
  if (row == "setup_load") {
    return "fixed overhead: span setup and engine load latency not hidden, " + grouped(n.pixels) +
           " pixels in " + grouped(n.spans) + " spans of " + fixed(per_span, 1) + " px on average";
  }
  return "input: " + row + " (gaps or back-pressure)";
}

// What lanes leave to the structure on a stream: "759,144 pixels in 230,466 beats of up to 4
// (96,358 spans of 7.9 px on average: lanes stay within a span), 0.304 cycles/px at the least".
}  // namespace

std::string lanes_floor(const StreamCounts& n, int lanes) {
  const uint64_t beats = n.beats;
  const auto ratio = [](uint64_t a, uint64_t b) {
    return b ? static_cast<double>(a) / static_cast<double>(b) : 0.0;
  };
  return grouped(n.pixels) + " pixels in " + grouped(beats) + " beats of up to " +
         std::to_string(lanes) + " (" + grouped(n.spans) + " spans of " +
         fixed(ratio(n.pixels, n.spans), 1) + " px on average: lanes stay within a span), " +
         fixed(ratio(beats, n.pixels)) + " cycles/px at the least";
}

StreamCounts& StreamCounts::operator+=(const StreamCounts& o) {
  triangles += o.triangles;
  spans += o.spans;
  materials += o.materials;
  table_words += o.table_words;
  pixels += o.pixels;
  beats += o.beats;
  return *this;
}

StreamCounts count(const CommandStream& stream, int lanes) {
  StreamCounts n;
  for (const Command& cmd : stream.commands) {
    if (std::holds_alternative<TriangleCmd>(cmd)) {
      ++n.triangles;
    } else if (const auto* s = std::get_if<SpanCmd>(&cmd)) {
      ++n.spans;
      n.pixels += static_cast<uint64_t>(s->length);
      n.beats += CycleEstimate::beats(static_cast<uint64_t>(s->length),
                                      static_cast<uint64_t>(std::max(1, lanes)));
    } else if (std::holds_alternative<MaterialCmd>(cmd)) {
      ++n.materials;
    } else if (const auto* t = std::get_if<TableCmd>(&cmd)) {
      n.table_words += t->entries.size();
    }
  }
  return n;
}

double cycles_per_pixel(const CycleEstimateRun& run) {
  return run.pixels ? static_cast<double>(run.cycles) / static_cast<double>(run.pixels) : 0.0;
}

std::string cycles_limit(const UnitConfig& unit, const CommandStream& stream,
                         const CycleEstimateRun& run) {
  return cycles_limit(unit, count(stream, unit.lanes), run);
}

std::string cycles_limit(const UnitConfig& unit, const StreamCounts& n,
                         const CycleEstimateRun& run) {
  if (!run.breakdown) throw std::logic_error("cycles_limit: the run has no breakdown");
  // The largest row other than pixels (rows() returns a value: keep it while pointing into it).
  const std::vector<CycleBreakdown::Row> rows = run.breakdown->rows();
  const CycleBreakdown::Row* row = nullptr;
  for (const auto& r : rows) {
    if (std::string(r.name) != "pixel" && (!row || r.cycles > row->cycles)) row = &r;
  }
  const double per_pixel =
      run.pixels ? static_cast<double>(row->cycles) / static_cast<double>(run.pixels) : 0.0;
  return resource(row->name, unit, n, run) + "; " + row->name + " " + grouped(row->cycles) +
         " of " + grouped(run.cycles) + " cycles, " + fixed(per_pixel) + " cycles/px";
}

std::string cycles_miss(const std::string& scene, const UnitConfig& unit,
                        const CommandStream& stream, const CycleEstimateRun& run, double target) {
  return cycles_miss(scene, unit, count(stream, unit.lanes), run, target);
}

std::string cycles_miss(const std::string& scene, const UnitConfig& unit, const StreamCounts& n,
                        const CycleEstimateRun& run, double target) {
  const double cpp = cycles_per_pixel(run);
  if (cpp <= target) return "";
  const std::string head = scene + ": " + fixed(cpp) + " cycles/px (" + grouped(run.cycles) +
                           " cycles, " + grouped(run.pixels) +
                           " pixels; cycle model, no gaps) over the " + target_text(target) +
                           " target; ";
  // Beats alone over the target: no structure helps, whatever the largest bubble row says.
  const double floor =
      run.pixels ? static_cast<double>(n.beats) / static_cast<double>(run.pixels) : 0.0;
  if (floor > target) return head + "pixel lanes: " + lanes_floor(n, unit.lanes);
  return head + cycles_limit(unit, n, run);
}

}  // namespace shadesim
