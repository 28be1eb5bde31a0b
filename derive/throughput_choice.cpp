#include "derive/throughput_choice.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <stdexcept>
#include <variant>

#include "derive/helpers.h"
#include "model/host_setup.h"

namespace shadesim {
namespace {

// One scene's command words for each site, encoded once: the knobs change no word of them, nor
// its beats on the unit's lanes, nor so its cycles target.
struct SceneStreams {
  std::string path;
  CommandStream unit_stream, host_stream;
  std::vector<uint64_t> unit_words, host_words;
  SceneCycles frame;  // its pixels and pixel beats (no cycles)
  double target = 0;  // cycles per pixel
};

// A stream's pixels and pixel beats on `lanes` lanes (no cycles): what its target is made of.
SceneCycles pixels_and_beats(const CommandStream& stream, int lanes) {
  SceneCycles f;
  for (const Command& cmd : stream.commands) {
    if (const auto* span = std::get_if<SpanCmd>(&cmd))
      f.pixels += static_cast<uint64_t>(span->length);
  }
  f.pixel_beats = pixel_beats(stream, lanes);
  return f;
}

std::vector<SceneStreams> prepare_streams(const FrameSet& frames, const DeriveOptions& options,
                                          const UnitConfig& unit, bool need_host) {
  UnitConfig base = unit;
  base.span_setup = SpanSetupSite::kUnit;
  base.tri_queue = 1;
  std::vector<SceneStreams> scenes;
  for (size_t i = 0; i < frames.size(); ++i) {
    SceneStreams s;
    s.path = frames.path(i);
    s.unit_stream = frames.at(i).encode(base).stream;
    s.unit_words = s.unit_stream.encode();
    s.frame = pixels_and_beats(s.unit_stream, unit.lanes);
    s.target = cycles_target(options, s.frame);
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
  // Within its target on every scene; stops at the first scene over it.
  bool meets(size_t candidate) {
    for (size_t s = 0; s < scenes_.size(); ++s) {
      if (cpp(candidate, s) > scenes_[s].target) return false;
    }
    return true;
  }
  // Cycles per pixel relative to the scene's target: scenes of different targets (per beat, on
  // several lanes) compare by it; with one target for all it orders them as their cycles do.
  double load(size_t candidate, size_t scene) {
    return cpp(candidate, scene) / scenes_[scene].target;
  }
  // The scene with the highest load (every scene measured).
  size_t worst_scene(size_t candidate) {
    size_t worst = 0;
    for (size_t s = 0; s < scenes_.size(); ++s) {
      if (load(candidate, s) > load(candidate, worst)) worst = s;
    }
    return worst;
  }
  double worst(size_t candidate) { return load(candidate, worst_scene(candidate)); }
  // Whether the candidate's worst scene is over its target.
  bool over(size_t candidate) {
    const size_t s = worst_scene(candidate);
    return cpp(candidate, s) > scenes_[s].target;
  }
  double worst_target(size_t candidate) { return scenes_[worst_scene(candidate)].target; }
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
size_t pick(Measurements& m, size_t count, bool& meets) {
  for (size_t i = 0; i < count; ++i) {
    if (m.meets(i)) {
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

  // "; NAME takes X cycles/px on SCENE (over T)", or "" where no such candidate is allowed.
  std::string operator()(const ThroughputKnobs& cheaper, const std::string& name) {
    const std::optional<size_t> i = index_of(candidates, cheaper);
    if (!i) return "";
    return "; " + name + " takes " + m.worst_text(*i) +
           (m.over(*i) ? " (over " + target_text(m.worst_target(*i)) + ")" : "");
  }
};

// The cycles target as the span_setup reason states it: "1.10 cycles/px" (one lane, or as given),
// or per beat on several lanes with each scene's figure: "1.10 cycles per beat of 4 lanes
// (0.3339 cycles/px on SCENE: 230,466 beats for 759,144 pixels)".
std::string target_words(const DeriveOptions& options, const UnitConfig& unit,
                         const std::vector<SceneStreams>& scenes) {
  if (options.max_cycles_per_pixel)
    return target_text(*options.max_cycles_per_pixel) + " cycles/px (--max-cycles-per-pixel)";
  if (unit.lanes == 1) return target_text(kMaxCyclesPerBeat) + " cycles/px";
  std::string per_scene;
  for (const SceneStreams& s : scenes) {
    per_scene += (per_scene.empty() ? "" : "; ") + target_text(s.target) + " cycles/px on " +
                 s.path + ": " + grouped(s.frame.pixel_beats) + " beats for " +
                 grouped(s.frame.pixels) + " pixels";
  }
  return target_text(kMaxCyclesPerBeat) + " cycles per beat of " + std::to_string(unit.lanes) +
         " lanes (" + per_scene + ")";
}

// The reasons of each knob of `chosen`.
void explain(const std::vector<ThroughputKnobs>& candidates, size_t chosen,
             const std::vector<SceneStreams>& scenes, const DeriveOptions& options,
             const UnitConfig& unit, Measurements& m, ThroughputChoice& c) {
  const ThroughputKnobs& k = candidates[chosen];
  const std::string target = target_words(options, unit, scenes);
  Step step{m, candidates};
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
    site += "the cheapest structure within " + target +
            " on every scene (cycle model, no gaps): " + k.to_string(unit) + ", worst " +
            m.worst_text(chosen) + "; of " + measured;
  } else {
    site += "no structure meets " + target +
            " on every scene (cycle model, no gaps); the fastest kept: " + k.to_string(unit) +
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

// The lanes' reason: as the unit has them (derive_config sets DeriveOptions::lanes), and on
// several lanes each scene's floor of one beat a cycle against kMaxCyclesPerBeat / lanes.
std::string lanes_why(const UnitConfig& unit, const std::vector<SceneStreams>& scenes) {
  if (unit.lanes == 1) return "one pixel a clock (--lanes 2 or 4: more pixels of a span a clock)";
  const double per_lane = kMaxCyclesPerBeat / unit.lanes;
  std::string why =
      std::to_string(unit.lanes) + " pixels of one span a clock, as requested (--lanes)";
  for (const SceneStreams& s : scenes) {
    const bool over =
        static_cast<double>(s.frame.pixel_beats) > per_lane * static_cast<double>(s.frame.pixels);
    why += "; " + s.path + ": " + lanes_floor(count(s.unit_stream, unit.lanes), unit.lanes) +
           (over ? ", over " : ", within ") + target_text(kMaxCyclesPerBeat) + " / " +
           std::to_string(unit.lanes) + " = " + fixed(per_lane);
  }
  return why;
}

}  // namespace

double cycles_target(const DeriveOptions& options, const SceneCycles& frame) {
  if (options.max_cycles_per_pixel) return *options.max_cycles_per_pixel;
  if (frame.pixels == 0) return kMaxCyclesPerBeat;
  // The ratio first: with one lane it is exactly 1, and the target exactly kMaxCyclesPerBeat.
  return kMaxCyclesPerBeat *
         (static_cast<double>(frame.pixel_beats) / static_cast<double>(frame.pixels));
}

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
  const std::vector<SceneStreams> scenes = prepare_streams(frames, options, unit, need_host);
  Measurements m(scenes, unit, candidates);
  ThroughputChoice c;
  const size_t chosen = pick(m, candidates.size(), c.meets);
  c.knobs = candidates[chosen];
  c.config = c.knobs.applied_to(unit);
  c.config.validate();
  for (size_t s = 0; s < scenes.size(); ++s) {
    c.cycles_per_pixel.push_back(m.cpp(chosen, s));
    c.targets.push_back(scenes[s].target);
    const CycleEstimateRun chosen_run = run_on(scenes[s], c.config);
    c.cycles.push_back({chosen_run.cycles, chosen_run.pixels, scenes[s].frame.pixel_beats});
    if (m.cpp(chosen, s) <= scenes[s].target) continue;
    const CycleEstimateRun run = run_on(scenes[s], c.config, true);
    c.misses.push_back(cycles_miss(scenes[s].path, c.config, stream_for(scenes[s], c.config), run,
                                   scenes[s].target));
  }
  explain(candidates, chosen, scenes, options, unit, m, c);
  c.lanes = lanes_why(unit, scenes);
  c.candidates_measured = m.runs();
  return c;
}

const DerivationRule kThroughputRule = {
    "port_words, tri_queue, span_setup, start_depth, material_buffers",
    "and a Schlick or W_m unit's timing: the cheapest structure that runs every scene at <= the "
    "cycles target (--max-cycles-per-pixel; by default 1.10 cycles per beat of the unit's lanes, "
    "1.10 cycles per pixel with one lane) by the cycle model, no gaps; pixels do not depend on "
    "them. Cheapest first: host span setup (the host sends each span's start values: no span "
    "setup, no coefficient banks, tri_queue 1) before unit setup, iterative before pipelined, "
    "fewer port words (1, 2, 4, 8), a shallower start bank (1, 2) or triangle queue (1..8), 1 "
    "material buffer before 2. Where none meets the target: the fastest, and each scene over it "
    "named with the resource that limits it (--port-words, --tri-queue, --span-setup hold a "
    "knob)"};

}  // namespace shadesim
