// shadesim cycles's engine (its options: sim/cli/cycles.cpp): cycles per pixel from the cycle model
// alone — the timing of rtl/shade_unit.sv without its datapath, exact to the cycle (co-simulation
// checks it against the RTL on every scanline) and far faster than simulating the RTL. With no gaps
// and no back-pressure every figure, the breakdown included, comes from the closed-form
// CycleEstimate (model/cycle_estimate.h); --clocked runs the clocked CycleModel too, which must
// agree.
#include "sim/engines/cycles.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "derive/cycles_limit.h"
#include "derive/throughput_choice.h"
#include "host/frame.h"
#include "model/coef_packing.h"
#include "model/cycle_estimate.h"
#include "model/cycle_model.h"
#include "model/start_packing.h"
#include "model/text_file.h"
#include "sim/engines/elapsed.h"
#include "sim/engines/unit_choice.h"
#include "sim/harness/cycle_run.h"

namespace shadesim {
namespace {

// The per-triangle figures of a no-gap run: how many triangles are setup- or fill-bound
// (TriangleCost::setup_bound) and the worst setup-bound ones, by decoder cycles over engine
// cycles.
struct TriangleSummary {
  size_t setup_bound = 0, fill_bound = 0;
  uint64_t setup_bound_excess = 0;  // sum of decoder - engine cycles over setup-bound triangles
  std::vector<TriangleCost> worst;

  TriangleSummary(const std::vector<TriangleCost>& triangles, int worst_n) {
    for (const TriangleCost& t : triangles) {
      if (t.setup_bound()) {
        ++setup_bound;
        setup_bound_excess += t.decoder_cycles - t.engine_cycles;
        worst.push_back(t);
      } else {
        ++fill_bound;
      }
    }
    const auto excess = [](const TriangleCost& t) { return t.decoder_cycles - t.engine_cycles; };
    const size_t n = std::min(worst.size(), static_cast<size_t>(std::max(worst_n, 0)));
    std::partial_sort(worst.begin(), worst.begin() + static_cast<std::ptrdiff_t>(n), worst.end(),
                      [&](const TriangleCost& a, const TriangleCost& b) {
                        return excess(a) != excess(b) ? excess(a) > excess(b) : a.index < b.index;
                      });
    worst.resize(n);
  }
  double share(size_t n) const {
    const size_t all = setup_bound + fill_bound;
    return all ? 100.0 * static_cast<double>(n) / static_cast<double>(all) : 0.0;
  }
};

// The first difference between the estimate and the clocked run, or "" when they agree.
std::string disagreement(const CycleEstimateRun& e, const CycleRun& c) {
  if (e.cycles != c.cycles)
    return "cycles " + std::to_string(e.cycles) + " vs " + std::to_string(c.cycles);
  if (e.breakdown) {
    const auto a = e.breakdown->rows(), b = c.breakdown.rows();
    for (size_t i = 0; i < a.size(); ++i) {
      if (a[i].cycles != b[i].cycles) {
        return std::string("breakdown ") + a[i].name + " " + std::to_string(a[i].cycles) + " vs " +
               std::to_string(b[i].cycles);
      }
    }
  }
  if (e.pixels != c.pixels)
    return "pixels " + std::to_string(e.pixels) + " vs " + std::to_string(c.pixels);
  if (e.scanlines.size() != c.scanlines.size()) {
    return "scanlines " + std::to_string(e.scanlines.size()) + " vs " +
           std::to_string(c.scanlines.size());
  }
  for (size_t i = 0; i < e.scanlines.size(); ++i) {
    if (e.scanlines[i].cycle != c.scanlines[i].cycle || e.scanlines[i].y != c.scanlines[i].y) {
      return "scanline y " + std::to_string(c.scanlines[i].y) + " done on cycle " +
             std::to_string(e.scanlines[i].cycle) + " vs " + std::to_string(c.scanlines[i].cycle);
    }
  }
  return "";
}

nlohmann::json cost_json(const TriangleCost& t) {
  return {{"index", t.index},
          {"xo", t.xo},
          {"yo", t.yo},
          {"words", t.words},
          {"spans", t.spans},
          {"pixels", t.pixels},
          {"decoder_cycles", t.decoder_cycles},
          {"engine_cycles", t.engine_cycles},
          {"setup_bound", t.setup_bound()}};
}

nlohmann::json triangles_json(const std::vector<TriangleCost>& all, const TriangleSummary& s) {
  nlohmann::json worst = nlohmann::json::array();
  for (const TriangleCost& t : s.worst) worst.push_back(cost_json(t));
  nlohmann::json each = nlohmann::json::array();
  for (const TriangleCost& t : all) {
    each.push_back({t.index, t.decoder_cycles, t.engine_cycles, t.setup_bound()});
  }
  return {{"count", all.size()},
          {"setup_bound", s.setup_bound},
          {"fill_bound", s.fill_bound},
          {"setup_bound_percent", s.share(s.setup_bound)},
          {"fill_bound_percent", s.share(s.fill_bound)},
          {"setup_bound_excess_cycles", s.setup_bound_excess},
          {"worst_setup_bound", worst},
          {"each_fields", {"index", "decoder_cycles", "engine_cycles", "setup_bound"}},
          {"each", each}};
}

// What `cycles` keeps of a frame: its unit, its command words and what they carry. The frame's
// stream is encoded a chunk at a time straight into words, and its set-up triangles are freed
// before the words are counted: a 3840x2160 frame never holds its whole command stream.
struct CyclesFrame {
  int width = 0, height = 0;
  UnitConfig config;
  EncodeStats stats;
  StreamCounts counts;
  std::vector<uint64_t> words;
};

CyclesFrame stream_frame(const std::string& scene_path, const FrameOptions& fo,
                         const std::string& choice) {
  CyclesFrame f;
  const Scene scene = load_scene(scene_path);
  f.width = scene.width;
  f.height = scene.height;
  f.config = frame_unit_on(scene, scene_path, fo, choice);
  // Each chunk's words kept apart while the geometry lives, joined once it is gone: the words
  // are never copied by doubling growth next to the set-up triangles.
  std::vector<std::vector<uint64_t>> chunks;
  {
    SetupOptions setup_options;
    setup_options.budget_lsb = fo.budget_lsb;
    setup_options.max_depth = fo.max_depth;
    setup_options.output_bits = f.config.out_bits;
    ProjectStats project;
    SetupResult setup;
    Visibility visibility;
    FrameTimings timings;
    prepare_geometry(scene, setup_options, project, setup, visibility, timings);
    f.stats = encode_frame_chunks(scene, f.config, setup, visibility, [&](CommandStream&& chunk) {
      f.counts += count(chunk, f.config.lanes);
      chunks.push_back(chunk.encode());
    });
  }
  f.words.reserve(f.stats.words);
  for (auto& c : chunks) {
    f.words.insert(f.words.end(), c.begin(), c.end());
    c = {};
  }
  return f;
}

// The frame on the unit --config names, with the throughput and structure options applied;
// `note` gets what the unit line says of --config (unit_choice_note).
CyclesFrame cycles_frame(const CyclesOptions& o, std::string& note) {
  FrameOptions fo;
  note = use_unit_choice(o.config, o.scene, o.widths, fo);
  // The throughput knobs given on the command line win over the unit's: "this unit, with a
  // wider port" is the question they answer.
  if (o.port_words > 0) fo.base.port_words = o.port_words;
  if (o.tri_queue > 0) fo.base.tri_queue = o.tri_queue;
  if (o.lanes > 0) fo.base.lanes = o.lanes;
  if (o.material_buffers > 0) fo.base.material_buffers = o.material_buffers;
  if (!o.span_setup.empty()) {
    fo.base.span_setup = parse_span_setup(o.span_setup, "--span-setup");
    // Host setup has no coefficient banks to queue; an explicit --tri-queue > 1 is refused.
    if (fo.base.host_setup() && o.tri_queue <= 0) fo.base.tri_queue = 1;
  }
  if (!o.diffuse_colour.empty())
    fo.base.diffuse_colour = parse_diffuse_colour(o.diffuse_colour, "--diffuse-colour");
  if (!o.specular.empty()) fo.specular_override = parse_specular_unit(o.specular, "--specular");
  if (o.channels > 0 || o.lights > 0) {
    // A fixed unit, as built: the scene must fit it.
    fo.fixed_unit = true;
    if (fo.specular_override) fo.base.specular.kind = *fo.specular_override;
    if (o.channels > 0) fo.base.channels = o.channels;
    if (o.lights > 0) fo.base.lights = o.lights;
  }
  return stream_frame(o.scene, fo, o.config);
}

// Everything one `cycles` run counts.
struct CyclesCount {
  CycleConfig timing;
  std::vector<uint64_t> words;
  bool no_stimulus = true;
  bool clocked = false;       // the clocked model ran
  CycleEstimateRun estimate;  // the closed form (per-triangle costs with any stimulus)
  CycleRun run;               // the figures reported
  uint64_t cycles_one_bank = 0;
  int64_t queue_hidden = 0;  // what the triangle queue hid
  double estimate_s = 0, model_s = 0;
};

CyclesCount count_cycles(const CyclesOptions& o, CyclesFrame& frame) {
  CyclesCount c;
  Stimulus stim;
  stim.seed = o.seed;
  stim.gap_pct = o.gap_pct;
  stim.max_gap = o.max_gap;
  stim.stall_pct = o.stall_pct;
  c.timing = CycleConfig::of(frame.config);
  c.words = std::move(frame.words);
  c.no_stimulus = o.gap_pct == 0 && o.stall_pct == 0;
  // The closed form: every figure without gaps or back-pressure, and the per-triangle costs
  // (defined on that schedule, so given with any stimulus).
  const auto t1 = std::chrono::steady_clock::now();
  c.estimate = CycleEstimate(c.timing).run(c.words, c.no_stimulus);
  c.estimate_s = seconds_since(t1);
  // The clocked model: every figure under gaps or back-pressure, and the check on request.
  c.clocked = o.clocked || !c.no_stimulus;
  if (c.clocked) {
    const auto t2 = std::chrono::steady_clock::now();
    c.run = run_cycle_model(c.words, stim, c.timing);
    c.model_s = seconds_since(t2);
    if (c.no_stimulus) {
      const std::string diff = disagreement(c.estimate, c.run);
      if (!diff.empty()) {
        throw std::logic_error(
            "the closed-form cycle estimate disagrees with the clocked cycle model on " + o.scene +
            ": " + diff + " (estimate vs clocked); please report it");
      }
    }
  } else {
    c.run.cycles = c.estimate.cycles;
    c.run.pixels = c.estimate.pixels;
    c.run.words = c.estimate.words;
    c.run.beats = c.estimate.beats;
    c.run.breakdown = *c.estimate.breakdown;
  }
  // What the triangle queue hid: the same stream and stimulus on the same unit with one bank.
  CycleConfig one_bank = c.timing;
  one_bank.tri_queue = 1;
  c.cycles_one_bank = c.timing.tri_queue == 1 ? c.run.cycles
                      : c.no_stimulus         ? CycleEstimate(one_bank).run(c.words).cycles
                                              : run_cycle_model(c.words, stim, one_bank).cycles;
  c.queue_hidden = static_cast<int64_t>(c.cycles_one_bank) - static_cast<int64_t>(c.run.cycles);
  return c;
}

// A triangle's words: the header and the packed coefficients (model/coef_packing.h), whose bits
// split by series.
struct TriangleWords {
  CoefLayout layout;
  int diffuse_bits = 0, specular_bits = 0, unpacked_words = 0;
  std::string term_bits;
  nlohmann::json term_bits_json = nlohmann::json::array();

  explicit TriangleWords(const UnitConfig& config) : layout(CoefLayout::of(config)) {
    int series_bits = 0;
    for (int t = 0; t < kTermsPerSeries; ++t) {
      series_bits += config.coef_term_bits(t);
      term_bits += (t ? "," : "") + std::to_string(config.coef_term_bits(t));
      term_bits_json.push_back(config.coef_term_bits(t));
    }
    diffuse_bits = series_bits * config.diffuse_series();
    specular_bits = series_bits * config.specular_series();
    unpacked_words = kTermsPerSeries * config.series_per_triangle();
  }
};

// Pixels per second at a clock: the clock over the run's cycles per pixel.
std::string speed_line(double clock_mhz, double cycles_per_px) {
  std::ostringstream os;
  os << "speed        " << std::fixed << std::setprecision(1) << clock_mhz / cycles_per_px
     << " Mpixel/s at " << clock_mhz << " MHz (the clock / " << std::setprecision(3)
     << cycles_per_px << " cycles per pixel)\n";
  return os.str();
}

double cycles_per_pixel(const CycleRun& run) {
  return run.pixels ? static_cast<double>(run.cycles) / static_cast<double>(run.pixels) : 0.0;
}

// What each triangle's (unit setup) or span's (host setup) payload costs on the port.
std::string payload_line(const UnitConfig& config, const TriangleWords& tw) {
  std::ostringstream payload;
  if (config.host_setup()) {
    const StartLayout starts = StartLayout::of(config);
    payload << "span         " << 1 + starts.words << " words (host span setup): 1 header + "
            << starts.words << " payload holding v, d, d2 of " << config.series_per_triangle()
            << " series, " << starts.value_bits << " bits each; no TRIANGLE on the port\n";
  } else {
    payload << "triangle     " << 1 + tw.layout.words << " words: 1 header + " << tw.layout.words
            << " payload (one coefficient a word: " << tw.unpacked_words << ") holding "
            << tw.diffuse_bits + tw.specular_bits << " coefficient bits: diffuse "
            << tw.diffuse_bits << " (" << config.diffuse_series() << " series), specular "
            << tw.specular_bits << " (" << config.specular_series() << " series); T0..T5 "
            << tw.term_bits << " bits\n";
  }
  return payload.str();
}

void print_cycles(const CyclesOptions& o, const CyclesFrame& frame, const CyclesCount& c,
                  const TriangleSummary& tris, double host_s, const std::string& unit_note) {
  const SlotTiming& slot = c.timing.slot;
  const CycleRun& run = c.run;
  const TriangleWords tw(frame.config);
  std::cout << "scene        " << o.scene << " (" << frame.width << "x" << frame.height << ")\n"
            << "unit         " << frame.config.to_string() << "  (" << unit_note << ")\n"
            << "specular     " << frame.config.specular.describe() << ": latency " << slot.latency
            << ", " << slot.interval << " cycle(s) per pixel\n"
            << "command port " << c.timing.port_words << " word(s) per beat, triangle queue "
            << c.timing.tri_queue << " (span queue " << c.timing.span_queue() << "), "
            << c.timing.lanes << " pixel lane(s), " << c.timing.material_buffers
            << " material buffer(s)\n"
            << "stimulus     seed " << o.seed << ", input gaps " << o.gap_pct << "% (max "
            << o.max_gap << "), back-pressure " << o.stall_pct << "%\n"
            << "stream       " << c.words.size() << " words: " << frame.stats.triangles << " tri ("
            << frame.stats.reorigins << " re-origin(s), offset_bits " << frame.config.offset_bits
            << "), " << frame.stats.spans << " spans, " << frame.stats.materials
            << " material loads, " << frame.stats.table_words << " table words\n"
            << payload_line(frame.config, tw) << "pixels       " << run.pixels
            << (c.timing.lanes > 1
                    ? " in " + std::to_string(run.breakdown.pixel) + " beats of up to " +
                          std::to_string(c.timing.lanes) + " (lanes within a span)"
                    : std::string())
            << "\n"
            << "cycles       " << run.cycles << "  (" << std::fixed << std::setprecision(3)
            << cycles_per_pixel(run) << " cycles per pixel)\n"
            << (o.clock_mhz > 0 ? speed_line(o.clock_mhz, cycles_per_pixel(run)) : std::string())
            << "queue        " << c.queue_hidden
            << " cycles hidden by the triangle queue (tri_queue 1: " << c.cycles_one_bank << ")\n";
  if (frame.config.host_setup()) {
    // No TRIANGLE on the port: every span's start values are its own command words.
    std::cout << "triangles    none on the port (host span setup: each SPAN brings its start "
                 "values; their words are command_words below)\n";
  } else {
    std::cout << "triangles    " << c.estimate.triangles.size()
              << " (no gaps, no back-pressure): " << tris.setup_bound << " setup-bound ("
              << std::setprecision(1) << tris.share(tris.setup_bound) << " %), " << tris.fill_bound
              << " fill-bound (" << tris.share(tris.fill_bound)
              << " %); setup-bound: more decoder cycles for its\n"
              << "             words than engine cycles for its pixels. The setup-bound ones need "
              << tris.setup_bound_excess << " decoder cycles more than their pixels.\n";
  }
  if (!tris.worst.empty()) {
    std::cout << "worst setup-bound triangles (decoder cycles - engine cycles):\n";
    for (const TriangleCost& t : tris.worst) {
      std::cout << "  #" << t.index << " origin (" << t.xo << ", " << t.yo << "): " << t.words
                << " words, " << t.spans << " spans, " << t.pixels << " px: " << t.decoder_cycles
                << " decoder cycles, " << t.engine_cycles << " engine cycles (+"
                << t.decoder_cycles - t.engine_cycles << ")\n";
    }
  }
  std::cout << "\nbreakdown    (every cycle charged to one reason; the rows sum to the total)\n";
  for (const auto& r : run.breakdown.rows()) {
    const double pct =
        run.cycles ? 100.0 * static_cast<double>(r.cycles) / static_cast<double>(run.cycles) : 0.0;
    std::cout << "  " << std::left << std::setw(15) << r.name << std::right << std::setw(12)
              << r.cycles << std::setw(8) << std::setprecision(1) << pct << " %  " << r.meaning
              << '\n';
  }
  const auto rate = [&](double s) {
    return s > 0 ? static_cast<double>(run.cycles) / s / 1e6 : 0.0;
  };
  std::cout << "\ntime         host " << std::setprecision(3) << host_s
            << " s, closed-form estimate " << c.estimate_s << " s (" << std::setprecision(1)
            << rate(c.estimate_s) << " M cycles/s)";
  if (c.clocked) {
    std::cout << ", clocked cycle model " << std::setprecision(3) << c.model_s << " s ("
              << std::setprecision(1) << rate(c.model_s) << " M cycles/s)";
    if (c.no_stimulus) std::cout << "; the two agree";
  }
  std::cout << "\n";
}

nlohmann::json cycles_json(const CyclesOptions& o, const CyclesFrame& frame, const CyclesCount& c,
                           const TriangleSummary& tris, double host_s) {
  const TriangleWords tw(frame.config);
  const CycleRun& run = c.run;
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& r : run.breakdown.rows()) {
    const double pct =
        run.cycles ? 100.0 * static_cast<double>(r.cycles) / static_cast<double>(run.cycles) : 0.0;
    rows.push_back(
        {{"name", r.name}, {"cycles", r.cycles}, {"percent", pct}, {"meaning", r.meaning}});
  }
  return {{"scene", o.scene},
          {"config", nlohmann::json::parse(config_to_json(frame.config))},
          {"unit_choice", o.config},
          {"slot", {{"latency", c.timing.slot.latency}, {"interval", c.timing.slot.interval}}},
          {"stimulus",
           {{"seed", o.seed},
            {"gap_pct", o.gap_pct},
            {"max_gap", o.max_gap},
            {"stall_pct", o.stall_pct}}},
          {"words", c.words.size()},
          {"beats", run.beats},
          {"triangle_words",
           {{"header", 1},
            {"payload", tw.layout.words},
            {"unpacked_payload", tw.unpacked_words},
            {"total", 1 + tw.layout.words},
            {"diffuse_bits", tw.diffuse_bits},
            {"specular_bits", tw.specular_bits},
            {"term_bits", tw.term_bits_json}}},
          {"material_buffers", c.timing.material_buffers},
          {"queue_hidden_cycles", c.queue_hidden},
          {"cycles_tri_queue_1", c.cycles_one_bank},
          {"pixels", run.pixels},
          {"pixel_beats", run.breakdown.pixel},
          {"cycles", run.cycles},
          {"cycles_per_pixel", cycles_per_pixel(run)},
          {"figures_from", c.no_stimulus ? "closed-form estimate" : "clocked cycle model"},
          {"clocked_check", c.no_stimulus && c.clocked},
          {"triangles", triangles_json(c.estimate.triangles, tris)},
          {"breakdown", rows},
          {"seconds",
           {{"host", host_s},
            {"estimate", c.estimate_s},
            {"cycle_model", c.clocked ? nlohmann::json(c.model_s) : nlohmann::json(nullptr)}}}};
}

// The frame's cycles target: --max-cycles-per-pixel where given, else config's own default for
// the unit's lanes (1.10 cycles per beat: 1.10 cycles per pixel with one lane), so `cycles`
// judges a unit as `config` chose it.
double cycles_target_of(const CyclesOptions& o, const CyclesFrame& frame) {
  DeriveOptions d;
  if (!std::isnan(o.max_cycles_per_pixel)) d.max_cycles_per_pixel = o.max_cycles_per_pixel;
  return cycles_target(d, SceneCycles{0, frame.counts.pixels, frame.counts.beats});
}

// The cycles target's warning: the unit's no-gap figure (gaps and back-pressure are the
// testbench's, not the unit's) over the target, naming the resource that limits it in config's
// words (cycles_miss). Empty within the target.
std::vector<std::string> cycles_warnings(const CyclesOptions& o, const CyclesFrame& frame,
                                         const CyclesCount& c, double target) {
  if (shadesim::cycles_per_pixel(c.estimate) <= target) return {};
  const CycleEstimateRun run =
      c.estimate.breakdown ? c.estimate : CycleEstimate(c.timing).run(c.words, true);
  std::string w = cycles_miss(o.scene, frame.config, frame.counts, run, target);
  if (!c.no_stimulus) {
    std::ostringstream os;
    os << std::fixed << std::setprecision(3) << cycles_per_pixel(c.run);
    w += " (judged without gaps; this run with its gaps and back-pressure: " + os.str() +
         " cycles/px)";
  }
  return {w};
}

}  // namespace

int run_cycles(const CyclesOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  std::string unit_note;
  CyclesFrame frame = cycles_frame(o, unit_note);
  const double host_s = seconds_since(t0);
  const CyclesCount c = count_cycles(o, frame);
  const TriangleSummary tris(c.estimate.triangles, o.worst);
  print_cycles(o, frame, c, tris, host_s, unit_note);
  const double target = cycles_target_of(o, frame);
  const std::vector<std::string> warnings = cycles_warnings(o, frame, c, target);
  for (const auto& w : warnings) std::cout << "warning      " << w << '\n';
  if (!o.json_path.empty()) {
    nlohmann::json j = cycles_json(o, frame, c, tris, host_s);
    j["max_cycles_per_pixel"] = target;
    if (o.clock_mhz > 0) {
      j["clock_mhz"] = o.clock_mhz;
      j["mpixel_per_s"] = o.clock_mhz / cycles_per_pixel(c.run);
    }
    j["warnings"] = warnings;
    write_text_file(o.json_path, j.dump(2) + '\n');
  }
  return 0;
}

}  // namespace shadesim
