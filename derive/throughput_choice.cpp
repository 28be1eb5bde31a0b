#include "derive/throughput_choice.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <variant>

#include "model/coef_packing.h"
#include "model/host_setup.h"
#include "model/start_packing.h"

namespace shadesim {
namespace {

std::string fixed(double x, int precision = 3) {
  std::ostringstream os;
  os << std::fixed;
  os.precision(precision);
  os << x;
  return os.str();
}

// 12345678 -> "12,345,678": the figures users compare with `cycles`' rows.
std::string grouped(uint64_t n) {
  std::string s = std::to_string(n);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3) s.insert(static_cast<size_t>(i), ",");
  return s;
}

// 1.1 -> "1.10", 1.125 -> "1.125": the target as the options spell it, at least two decimals.
std::string target_text(double target) {
  std::string s = fixed(target, 6);
  while (s.size() > s.find('.') + 3 && s.back() == '0') s.pop_back();
  return s;
}

// One scene's command words for each site, encoded once: the knobs change no word of them.
struct SceneStreams {
  std::string path;
  CommandStream unit_stream, host_stream;
  std::vector<uint64_t> unit_words, host_words;
};

std::vector<SceneStreams> prepare_streams(const FrameSet& frames, const UnitConfig& unit,
                                          bool need_host) {
  UnitConfig base = unit;
  base.span_setup = SpanSetupSite::kUnit;
  base.tri_queue = 1;
  std::vector<SceneStreams> scenes;
  for (size_t i = 0; i < frames.size(); ++i) {
    SceneStreams s;
    s.path = frames.path(i);
    s.unit_stream = frames.at(i).encode(base).stream;
    s.unit_words = s.unit_stream.encode();
    // The encoder's own route to a host-setup stream (host/encode.cpp): the same frame, each
    // span's start values formed from the unit-setup stream.
    if (need_host) {
      s.host_stream = with_host_setup(s.unit_stream);
      s.host_words = s.host_stream.encode();
    }
    scenes.push_back(std::move(s));
  }
  return scenes;
}

const CommandStream& stream_for(const SceneStreams& s, const UnitConfig& c) {
  return c.host_setup() ? s.host_stream : s.unit_stream;
}

CycleEstimateRun run_on(const SceneStreams& s, const UnitConfig& c, bool breakdown = false) {
  return CycleEstimate(CycleConfig::of(c))
      .run(c.host_setup() ? s.host_words : s.unit_words, breakdown);
}

// Each candidate's cycles per pixel, scene by scene, measured once and only when asked for.
class Measurements {
 public:
  Measurements(const std::vector<SceneStreams>& scenes, const UnitConfig& unit,
               const std::vector<ThroughputKnobs>& candidates)
      : scenes_(scenes), unit_(unit), candidates_(candidates) {
    cpp_.assign(candidates.size(), std::vector<std::optional<double>>(scenes.size()));
  }

  double cpp(size_t candidate, size_t scene) {
    std::optional<double>& v = cpp_[candidate][scene];
    if (!v) {
      v = cycles_per_pixel(run_on(scenes_[scene], candidates_[candidate].applied_to(unit_)));
      ++runs_;
    }
    return *v;
  }
  // Within the target on every scene; stops at the first scene over it.
  bool meets(size_t candidate, double target) {
    for (size_t s = 0; s < scenes_.size(); ++s) {
      if (cpp(candidate, s) > target) return false;
    }
    return true;
  }
  // The scene with the most cycles per pixel (every scene measured).
  size_t worst_scene(size_t candidate) {
    size_t worst = 0;
    for (size_t s = 0; s < scenes_.size(); ++s) {
      if (cpp(candidate, s) > cpp(candidate, worst)) worst = s;
    }
    return worst;
  }
  double worst(size_t candidate) { return cpp(candidate, worst_scene(candidate)); }
  // "1.234 cycles/px on SCENE" for the candidate's worst scene.
  std::string worst_text(size_t candidate) {
    const size_t s = worst_scene(candidate);
    return fixed(cpp(candidate, s)) + " cycles/px on " + scenes_[s].path;
  }
  size_t runs() const { return runs_; }

 private:
  const std::vector<SceneStreams>& scenes_;
  const UnitConfig& unit_;
  const std::vector<ThroughputKnobs>& candidates_;
  std::vector<std::vector<std::optional<double>>> cpp_;
  size_t runs_ = 0;
};

bool same(const ThroughputKnobs& a, const ThroughputKnobs& b) {
  return a.span_setup == b.span_setup && a.pipelined == b.pipelined &&
         a.material_buffers == b.material_buffers && a.port_words == b.port_words &&
         a.depth == b.depth;
}

std::optional<size_t> index_of(const std::vector<ThroughputKnobs>& candidates,
                               const ThroughputKnobs& k) {
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (same(candidates[i], k)) return i;
  }
  return std::nullopt;
}

// The chosen candidate: the first (cheapest) within the target on every scene, else the cheapest
// within kFastestTolerance of the fastest. Sets `meets`.
size_t pick(Measurements& m, size_t count, double target, bool& meets) {
  for (size_t i = 0; i < count; ++i) {
    if (m.meets(i, target)) {
      meets = true;
      return i;
    }
  }
  meets = false;
  double fastest = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < count; ++i) fastest = std::min(fastest, m.worst(i));
  for (size_t i = 0; i < count; ++i) {
    if (m.worst(i) <= fastest * (1 + kFastestTolerance)) return i;
  }
  return 0;
}

// Why a knob has its value: the candidate one step cheaper in it alone, and what it takes.
struct Step {
  Measurements& m;
  const std::vector<ThroughputKnobs>& candidates;
  double target;

  // "; NAME takes X cycles/px on SCENE (over T)", or "" where no such candidate is allowed.
  std::string operator()(const ThroughputKnobs& cheaper, const std::string& name) {
    const std::optional<size_t> i = index_of(candidates, cheaper);
    if (!i) return "";
    const bool over = m.worst(*i) > target;
    return "; " + name + " takes " + m.worst_text(*i) +
           (over ? " (over " + target_text(target) + ")" : "");
  }
};

// The reasons of each knob of `chosen`.
void explain(const std::vector<ThroughputKnobs>& candidates, size_t chosen,
             const DeriveOptions& options, const UnitConfig& unit, Measurements& m,
             ThroughputChoice& c) {
  const ThroughputKnobs& k = candidates[chosen];
  const double target = options.max_cycles_per_pixel;
  Step step{m, candidates, target};
  const bool host = k.span_setup == SpanSetupSite::kHost;
  ThroughputKnobs cheaper = k;
  // Port words.
  cheaper.port_words = k.port_words / 2;
  c.port_words = options.port_words  ? "as requested (--port-words)"
                 : k.port_words == 1 ? "the narrowest port"
                                     : std::to_string(k.port_words) + " words a beat" +
                                           step(cheaper, std::to_string(cheaper.port_words));
  cheaper = k;
  // The start bank's or the triangle queue's depth.
  cheaper.depth = k.depth - 1;
  const std::string depth_why =
      k.depth == 1 ? "the shallowest"
                   : std::to_string(k.depth) + step(cheaper, std::to_string(cheaper.depth));
  cheaper = k;
  c.tri_queue = host                ? "1: host span setup has no coefficient banks to queue"
                : options.tri_queue ? "as requested (--tri-queue)"
                                    : depth_why;
  c.start_depth = host ? depth_why : "";
  // Material buffers.
  cheaper.material_buffers = 1;
  c.material_buffers = k.material_buffers == 1
                           ? "one: a MATERIAL or TABLE waits for the empty datapath"
                           : "two: a MATERIAL or per-material TABLE loads the bank no span in "
                             "flight reads" +
                                 step(cheaper, "one");
  cheaper = k;
  // Timing.
  cheaper.pipelined = false;
  if (has_timing_choice(unit)) {
    c.timing =
        k.pipelined ? "pipelined (one pixel a cycle)" + step(cheaper, "iterative") : "iterative";
  }
  // The site, and the summary of the search.
  const std::string measured = std::to_string(candidates.size()) +
                               " candidates, cheapest first (host before unit setup, iterative "
                               "before pipelined, fewer port words, a shallower start bank or "
                               "triangle queue, 1 material buffer before 2), " +
                               std::to_string(m.runs()) + " cycle-model runs";
  std::string site = options.span_setup ? "as requested (--span-setup); " : "";
  if (c.meets) {
    site += "the cheapest structure within " + target_text(target) +
            " cycles/px on every scene (cycle model, no gaps): " + k.to_string(unit) + ", worst " +
            m.worst_text(chosen) + "; of " + measured;
  } else {
    site +=
        "no structure meets " + target_text(target) +
        " cycles/px on every scene (cycle model, no gaps); the fastest kept: " + k.to_string(unit) +
        ", worst " + m.worst_text(chosen) + "; of " + measured;
  }
  if (!host && !options.span_setup) {
    // Host setup's fastest candidate: what unit setup was bought for.
    std::optional<size_t> best;
    for (size_t i = 0; i < candidates.size(); ++i) {
      if (candidates[i].span_setup == SpanSetupSite::kHost &&
          (!best || m.worst(i) < m.worst(*best)))
        best = i;
    }
    if (best) {
      site += "; host setup's fastest (" + candidates[*best].to_string(unit) + ") takes " +
              m.worst_text(*best);
    }
  }
  c.span_setup = site;
}

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

UnitConfig ThroughputKnobs::applied_to(const UnitConfig& unit) const {
  UnitConfig c = unit;
  c.span_setup = span_setup;
  c.port_words = port_words;
  c.material_buffers = material_buffers;
  if (span_setup == SpanSetupSite::kHost) {
    c.tri_queue = 1;
    c.start_depth = depth;
  } else {
    c.tri_queue = depth;
  }
  const UnitTiming timing = pipelined ? UnitTiming::kPipelined : UnitTiming::kIterative;
  if (c.specular.kind == SpecularUnitKind::kSchlick) c.specular.schlick.timing = timing;
  if (c.specular.kind == SpecularUnitKind::kWpow) {
    c.specular.wpow.timing = timing;
    // A split squaring is a pipelined unit's clock knob; an iterative unit squares in one cycle.
    if (!pipelined) c.specular.wpow.square_stages = 1;
  }
  return c;
}

std::string ThroughputKnobs::to_string(const UnitConfig& unit) const {
  const bool host = span_setup == SpanSetupSite::kHost;
  return std::string(host ? "host" : "unit") + " setup, P=" + std::to_string(port_words) +
         (host ? ", start_depth " : ", tri_queue ") + std::to_string(depth) + ", " +
         std::to_string(material_buffers) + " material buffer(s)" +
         (has_timing_choice(unit) ? (pipelined ? ", pipelined" : ", iterative") : "");
}

bool has_timing_choice(const UnitConfig& unit) {
  return unit.specular.kind == SpecularUnitKind::kSchlick ||
         unit.specular.kind == SpecularUnitKind::kWpow;
}

std::vector<ThroughputKnobs> throughput_candidates(const UnitConfig& unit,
                                                   const DeriveOptions& options) {
  std::vector<ThroughputKnobs> out;
  const bool timing = has_timing_choice(unit);
  const bool unit_pipelined = (unit.specular.kind == SpecularUnitKind::kSchlick &&
                               unit.specular.schlick.timing == UnitTiming::kPipelined) ||
                              (unit.specular.kind == SpecularUnitKind::kWpow &&
                               unit.specular.wpow.timing == UnitTiming::kPipelined);
  for (const SpanSetupSite site : {SpanSetupSite::kHost, SpanSetupSite::kUnit}) {
    if (options.span_setup && *options.span_setup != site) continue;
    const bool host = site == SpanSetupSite::kHost;
    if (host && options.tri_queue && *options.tri_queue != 1) continue;
    for (const bool pipelined : {false, true}) {
      if (!timing && pipelined != unit_pipelined) continue;
      for (const int port : {1, 2, 4, 8}) {
        if (options.port_words && *options.port_words != port) continue;
        for (int depth = 1; depth <= (host ? 2 : 8); ++depth) {
          if (!host && options.tri_queue && *options.tri_queue != depth) continue;
          for (const int buffers : {1, 2}) out.push_back({site, pipelined, buffers, port, depth});
        }
      }
    }
  }
  if (out.empty()) {
    throw std::invalid_argument(
        "throughput: no candidate for the requests: tri_queue must be 1 "
        "with span_setup host, got " +
        std::to_string(options.tri_queue.value_or(1)));
  }
  return out;
}

ThroughputChoice choose_throughput(const FrameSet& frames, const DeriveOptions& options,
                                   const UnitConfig& unit) {
  const std::vector<ThroughputKnobs> candidates = throughput_candidates(unit, options);
  const bool need_host = std::any_of(candidates.begin(), candidates.end(), [](const auto& k) {
    return k.span_setup == SpanSetupSite::kHost;
  });
  const std::vector<SceneStreams> scenes = prepare_streams(frames, unit, need_host);
  Measurements m(scenes, unit, candidates);
  ThroughputChoice c;
  const size_t chosen = pick(m, candidates.size(), options.max_cycles_per_pixel, c.meets);
  c.knobs = candidates[chosen];
  c.config = c.knobs.applied_to(unit);
  c.config.validate();
  for (size_t s = 0; s < scenes.size(); ++s) {
    c.cycles_per_pixel.push_back(m.cpp(chosen, s));
    const CycleEstimateRun chosen_run = run_on(scenes[s], c.config);
    c.cycles.push_back({chosen_run.cycles, chosen_run.pixels});
    if (m.cpp(chosen, s) <= options.max_cycles_per_pixel) continue;
    const CycleEstimateRun run = run_on(scenes[s], c.config, true);
    c.misses.push_back(cycles_miss(scenes[s].path, c.config, stream_for(scenes[s], c.config), run,
                                   options.max_cycles_per_pixel));
  }
  explain(candidates, chosen, options, unit, m, c);
  c.candidates_measured = m.runs();
  return c;
}

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
