#include "derive/cycles_limit.h"

#include <stdexcept>
#include <variant>
#include <vector>

#include "derive/helpers.h"
#include "model/coef_packing.h"
#include "model/cycle_model.h"
#include "model/start_packing.h"

namespace shadesim {
namespace {

struct StreamCounts {
  uint64_t triangles = 0, spans = 0, materials = 0, table_words = 0, pixels = 0;
};

StreamCounts count(const CommandStream& stream) {
  StreamCounts n;
  for (const Command& cmd : stream.commands) {
    if (std::holds_alternative<TriangleCmd>(cmd)) {
      ++n.triangles;
    } else if (const auto* s = std::get_if<SpanCmd>(&cmd)) {
      ++n.spans;
      n.pixels += static_cast<uint64_t>(s->length);
    } else if (std::holds_alternative<MaterialCmd>(cmd)) {
      ++n.materials;
    } else if (const auto* t = std::get_if<TableCmd>(&cmd)) {
      n.table_words += t->entries.size();
    }
  }
  return n;
}

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

}  // namespace

double cycles_per_pixel(const CycleEstimateRun& run) {
  return run.pixels ? static_cast<double>(run.cycles) / static_cast<double>(run.pixels) : 0.0;
}

std::string cycles_limit(const UnitConfig& unit, const CommandStream& stream,
                         const CycleEstimateRun& run) {
  if (!run.breakdown) throw std::logic_error("cycles_limit: the run has no breakdown");
  // The largest row other than pixels (rows() returns a value: keep it while pointing into it).
  const std::vector<CycleBreakdown::Row> rows = run.breakdown->rows();
  const CycleBreakdown::Row* row = nullptr;
  for (const auto& r : rows) {
    if (std::string(r.name) != "pixel" && (!row || r.cycles > row->cycles)) row = &r;
  }
  const StreamCounts n = count(stream);
  const double per_pixel =
      run.pixels ? static_cast<double>(row->cycles) / static_cast<double>(run.pixels) : 0.0;
  return resource(row->name, unit, n, run) + "; " + row->name + " " + grouped(row->cycles) +
         " of " + grouped(run.cycles) + " cycles, " + fixed(per_pixel) + " cycles/px";
}

std::string cycles_miss(const std::string& scene, const UnitConfig& unit,
                        const CommandStream& stream, const CycleEstimateRun& run, double target) {
  const double cpp = cycles_per_pixel(run);
  if (cpp <= target) return "";
  return scene + ": " + fixed(cpp) + " cycles/px (" + grouped(run.cycles) + " cycles, " +
         grouped(run.pixels) + " pixels; cycle model, no gaps) over the " + target_text(target) +
         " target; " + cycles_limit(unit, stream, run);
}

}  // namespace shadesim
