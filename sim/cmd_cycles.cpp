// shadesim cycles SCENE: cycles per pixel from the cycle model alone — the timing of
// rtl/shade_unit.sv without its datapath, exact to the cycle (co-simulation checks it against
// the RTL on every scanline) and far faster than simulating the RTL. With no gaps and no
// back-pressure every figure, the breakdown included, comes from the closed-form CycleEstimate
// (model/cycle_estimate.h); --clocked runs the clocked CycleModel too, which must agree.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "host/frame.h"
#include "model/coef_packing.h"
#include "model/cycle_estimate.h"
#include "model/cycle_model.h"
#include "model/start_packing.h"
#include "sim/commands.h"
#include "sim/config_option.h"
#include "sim/harness/cycle_run.h"
#include "sim/output_paths.h"
#include "sim/stimulus_options.h"
#include "sim/width_options.h"

namespace shadesim {
namespace {

struct CyclesOptions {
  std::string scene;
  WidthOptions widths;
  std::string specular;
  int channels = 0;  // 0: what the scene needs
  int lights = 0;
  int port_words = 0;  // 0: not given (1, or the --config file's)
  int tri_queue = 0;
  int lanes = 0;
  int material_buffers = 0;
  uint64_t seed = 1;
  int gap_pct = 0, max_gap = 1, stall_pct = 0;
  std::string json_path;
  std::string config_path;  // --config: the unit is exactly this file's
  bool clocked = false;     // also the clocked model when the closed form applies; must agree
  int worst = 5;            // setup-bound triangles listed
};

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

int run_cycles(const CyclesOptions& o) {
  FrameOptions fo;
  if (!o.config_path.empty()) {
    use_config_file(o.config_path, fo);
  } else {
    fo.base = o.widths.to_config();
  }
  // The throughput knobs given on the command line win over the file's: "this unit, with a
  // wider port" is the question they answer.
  if (o.port_words > 0) fo.base.port_words = o.port_words;
  if (o.tri_queue > 0) fo.base.tri_queue = o.tri_queue;
  if (o.lanes > 0) fo.base.lanes = o.lanes;
  if (o.material_buffers > 0) fo.base.material_buffers = o.material_buffers;
  if (!o.specular.empty()) fo.specular_override = parse_specular_unit(o.specular, "--specular");
  if (o.channels > 0 || o.lights > 0) {
    // A fixed unit, as built: the scene must fit it.
    fo.fixed_unit = true;
    if (fo.specular_override) fo.base.specular.kind = *fo.specular_override;
    if (o.channels > 0) fo.base.channels = o.channels;
    if (o.lights > 0) fo.base.lights = o.lights;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const PreparedFrame frame = prepare_frame_on(o.scene, fo, o.config_path);
  const double host_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  Stimulus stim;
  stim.seed = o.seed;
  stim.gap_pct = o.gap_pct;
  stim.max_gap = o.max_gap;
  stim.stall_pct = o.stall_pct;
  const CycleConfig unit_timing = CycleConfig::of(frame.config);
  const SlotTiming& timing = unit_timing.slot;
  const std::vector<uint64_t> words = frame.encoded.stream.encode();
  const bool no_stimulus = o.gap_pct == 0 && o.stall_pct == 0;
  // The closed form: every figure without gaps or back-pressure, and the per-triangle costs
  // (defined on that schedule, so given with any stimulus).
  const CycleEstimate estimate(unit_timing);
  const auto t1 = std::chrono::steady_clock::now();
  const CycleEstimateRun est = estimate.run(words, no_stimulus);
  const double estimate_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  // The clocked model: every figure under gaps or back-pressure, and the check on request.
  const bool clocked = o.clocked || !no_stimulus;
  CycleRun run;
  double model_s = 0;
  if (clocked) {
    const auto t2 = std::chrono::steady_clock::now();
    run = run_cycle_model(words, stim, unit_timing);
    model_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t2).count();
    if (no_stimulus) {
      const std::string diff = disagreement(est, run);
      if (!diff.empty()) {
        throw std::logic_error(
            "the closed-form cycle estimate disagrees with the clocked cycle model on " + o.scene +
            ": " + diff + " (estimate vs clocked); please report it");
      }
    }
  } else {
    run.cycles = est.cycles;
    run.pixels = est.pixels;
    run.words = est.words;
    run.beats = est.beats;
    run.breakdown = *est.breakdown;
  }
  // What the triangle queue hid: the same stream and stimulus on the same unit with one bank.
  CycleConfig one_bank = unit_timing;
  one_bank.tri_queue = 1;
  const uint64_t cycles_one_bank = unit_timing.tri_queue == 1 ? run.cycles
                                   : no_stimulus ? CycleEstimate(one_bank).run(words).cycles
                                                 : run_cycle_model(words, stim, one_bank).cycles;
  const int64_t queue_hid =
      static_cast<int64_t>(cycles_one_bank) - static_cast<int64_t>(run.cycles);
  const TriangleSummary tris(est.triangles, o.worst);
  // Words per triangle by series (model/command_stream.h: a header, then T0..T5 per series).
  // A triangle's words: the header and the packed coefficients (model/coef_packing.h), whose
  // bits split by series.
  const CoefLayout layout = CoefLayout::of(frame.config);
  int series_bits = 0;
  std::string term_bits;
  nlohmann::json term_bits_json = nlohmann::json::array();
  for (int t = 0; t < kTermsPerSeries; ++t) {
    series_bits += frame.config.coef_term_bits(t);
    term_bits += (t ? "," : "") + std::to_string(frame.config.coef_term_bits(t));
    term_bits_json.push_back(frame.config.coef_term_bits(t));
  }
  const int diffuse_bits = series_bits * frame.config.diffuse_series();
  const int specular_bits = series_bits * frame.config.specular_series();
  const int unpacked_words = kTermsPerSeries * frame.config.series_per_triangle();

  const double cpp =
      run.pixels ? static_cast<double>(run.cycles) / static_cast<double>(run.pixels) : 0.0;
  // What each triangle's (unit setup) or span's (host setup) payload costs on the port.
  std::ostringstream payload;
  if (frame.config.host_setup()) {
    const StartLayout starts = StartLayout::of(frame.config);
    payload << "span         " << 1 + starts.words << " words (host span setup): 1 header + "
            << starts.words << " payload holding v, d, d2 of " << frame.config.series_per_triangle()
            << " series, " << starts.value_bits << " bits each; no TRIANGLE on the port\n";
  } else {
    payload << "triangle     " << 1 + layout.words << " words: 1 header + " << layout.words
            << " payload (one coefficient a word: " << unpacked_words << ") holding "
            << diffuse_bits + specular_bits << " coefficient bits: diffuse " << diffuse_bits << " ("
            << frame.config.diffuse_series() << " series), specular " << specular_bits << " ("
            << frame.config.specular_series() << " series); T0..T5 " << term_bits << " bits\n";
  }
  const std::string payload_line = payload.str();
  std::cout << "scene        " << o.scene << " (" << frame.scene.width << "x" << frame.scene.height
            << ")\n"
            << "unit         " << frame.config.to_string() << "\n"
            << "specular     " << frame.config.specular.describe() << ": latency " << timing.latency
            << ", " << timing.interval << " cycle(s) per pixel\n"
            << "command port " << unit_timing.port_words << " word(s) per beat, triangle queue "
            << unit_timing.tri_queue << " (span queue " << unit_timing.span_queue() << "), "
            << unit_timing.lanes << " pixel lane(s), " << unit_timing.material_buffers
            << " material buffer(s)\n"
            << "stimulus     seed " << o.seed << ", input gaps " << o.gap_pct << "% (max "
            << o.max_gap << "), back-pressure " << o.stall_pct << "%\n"
            << "stream       " << words.size() << " words: " << frame.encoded.stats.triangles
            << " tri (" << frame.encoded.stats.reorigins << " re-origin(s), offset_bits "
            << frame.encoded.stream.config.offset_bits << "), " << frame.encoded.stats.spans
            << " spans, " << frame.encoded.stats.materials << " material loads, "
            << frame.encoded.stats.table_words << " table words\n"
            << payload_line << "pixels       " << run.pixels
            << (unit_timing.lanes > 1
                    ? " in " + std::to_string(run.breakdown.pixel) + " beats of up to " +
                          std::to_string(unit_timing.lanes) + " (lanes within a span)"
                    : std::string())
            << "\n"
            << "cycles       " << run.cycles << "  (" << std::fixed << std::setprecision(3) << cpp
            << " cycles per pixel)\n"
            << "queue        " << queue_hid
            << " cycles hidden by the triangle queue (tri_queue 1: " << cycles_one_bank << ")\n"
            << "triangles    " << est.triangles.size()
            << " (no gaps, no back-pressure): " << tris.setup_bound << " setup-bound ("
            << std::setprecision(1) << tris.share(tris.setup_bound) << " %), " << tris.fill_bound
            << " fill-bound (" << tris.share(tris.fill_bound)
            << " %); setup-bound: more decoder cycles for its\n"
            << "             words than engine cycles for its pixels. The setup-bound ones need "
            << tris.setup_bound_excess << " decoder cycles more than their pixels.\n";
  if (!tris.worst.empty()) {
    std::cout << "worst setup-bound triangles (decoder cycles - engine cycles):\n";
    for (const TriangleCost& t : tris.worst) {
      std::cout << "  #" << t.index << " origin (" << t.xo << ", " << t.yo << "): " << t.words
                << " words, " << t.spans << " spans, " << t.pixels << " px: " << t.decoder_cycles
                << " decoder cycles, " << t.engine_cycles << " engine cycles (+"
                << t.decoder_cycles - t.engine_cycles << ")\n";
    }
  }
  nlohmann::json rows = nlohmann::json::array();
  std::cout << "\nbreakdown    (every cycle charged to one reason; the rows sum to the total)\n";
  for (const auto& r : run.breakdown.rows()) {
    const double pct =
        run.cycles ? 100.0 * static_cast<double>(r.cycles) / static_cast<double>(run.cycles) : 0.0;
    std::cout << "  " << std::left << std::setw(15) << r.name << std::right << std::setw(12)
              << r.cycles << std::setw(8) << std::setprecision(1) << pct << " %  " << r.meaning
              << '\n';
    rows.push_back(
        {{"name", r.name}, {"cycles", r.cycles}, {"percent", pct}, {"meaning", r.meaning}});
  }
  const auto rate = [&](double s) {
    return s > 0 ? static_cast<double>(run.cycles) / s / 1e6 : 0.0;
  };
  std::cout << "\ntime         host " << std::setprecision(3) << host_s
            << " s, closed-form estimate " << estimate_s << " s (" << std::setprecision(1)
            << rate(estimate_s) << " M cycles/s)";
  if (clocked) {
    std::cout << ", clocked cycle model " << std::setprecision(3) << model_s << " s ("
              << std::setprecision(1) << rate(model_s) << " M cycles/s)";
    if (no_stimulus) std::cout << "; the two agree";
  }
  std::cout << "\n";
  if (!o.json_path.empty()) {
    nlohmann::json j = {
        {"scene", o.scene},
        {"config", nlohmann::json::parse(config_to_json(frame.config))},
        {"slot", {{"latency", timing.latency}, {"interval", timing.interval}}},
        {"stimulus",
         {{"seed", o.seed},
          {"gap_pct", o.gap_pct},
          {"max_gap", o.max_gap},
          {"stall_pct", o.stall_pct}}},
        {"words", words.size()},
        {"beats", run.beats},
        {"triangle_words",
         {{"header", 1},
          {"payload", layout.words},
          {"unpacked_payload", unpacked_words},
          {"total", 1 + layout.words},
          {"diffuse_bits", diffuse_bits},
          {"specular_bits", specular_bits},
          {"term_bits", term_bits_json}}},
        {"material_buffers", unit_timing.material_buffers},
        {"queue_hidden_cycles", queue_hid},
        {"cycles_tri_queue_1", cycles_one_bank},
        {"pixels", run.pixels},
        {"pixel_beats", run.breakdown.pixel},
        {"cycles", run.cycles},
        {"cycles_per_pixel", cpp},
        {"figures_from", no_stimulus ? "closed-form estimate" : "clocked cycle model"},
        {"clocked_check", no_stimulus && clocked},
        {"triangles", triangles_json(est.triangles, tris)},
        {"breakdown", rows},
        {"seconds",
         {{"host", host_s},
          {"estimate", estimate_s},
          {"cycle_model", clocked ? nlohmann::json(model_s) : nlohmann::json(nullptr)}}}};
    std::ofstream os(o.json_path);
    if (!os) throw std::runtime_error(o.json_path + ": cannot open for writing");
    os << j.dump(2) << '\n';
  }
  return 0;
}

}  // namespace

void register_cycles(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<CyclesOptions>();
  CLI::App* sub = app.add_subcommand(
      "cycles",
      "Estimate cycles per pixel for a scene from the cycle model alone (the RTL's control, clock "
      "by\n"
      "clock, without its datapath: exact to the cycle, far faster than co-simulation), with a\n"
      "breakdown of where the cycles go: pixels, span setup, unit stalls, table reloads, material\n"
      "drains, command words and gaps, back-pressure. With no gaps and no back-pressure (the "
      "default)\n"
      "every figure, the breakdown included, comes from a closed-form recurrence over commands "
      "and\n"
      "spans (model/cycle_estimate.h), equal to the clocked model's (--clocked runs both and "
      "checks).\n"
      "Per triangle: its decoder cycles are the cycles on which the decoder takes its words (the\n"
      "TRIANGLE header, its coefficient words, the SPAN headers up to the next TRIANGLE; one item "
      "a\n"
      "cycle, waiting not counted); its engine cycles are its pixels' beats x the specular slot's\n"
      "interval. It is setup-bound if its decoder cycles exceed its engine cycles, else "
      "fill-bound.");
  sub->add_option("scene", o->scene, "scene JSON file")->required()->check(CLI::ExistingFile);
  sub->add_option("--specular", o->specular,
                  "specular unit: ideal|lut|schlick|wpow (default: the scene's)");
  sub->add_option("--channels", o->channels,
                  "build with this many channels (default: what the scene needs)")
      ->check(CLI::IsMember({1, 3}));
  sub->add_option("--lights", o->lights,
                  "build with series for this many lights (default: the scene's)")
      ->check(CLI::Range(1, 8));
  sub->add_option(
         "--port-words", o->port_words,
         "command port width: 64-bit words per handshake (default 1, or the --config file's;\n"
         "given, it overrides the file's)")
      ->check(CLI::IsMember({1, 2, 4, 8}));
  sub->add_option(
         "--tri-queue", o->tri_queue,
         "triangle queue depth: coefficient banks; > 1 adds a span queue (default 1, or the\n"
         "--config file's; given, it overrides the file's)")
      ->check(CLI::Range(1, 8));
  sub->add_option(
         "--lanes", o->lanes,
         "pixel lanes: pixels of one span per clock (k-step forward differences, lane j at\n"
         "x0 + j; default 1, or the --config file's; given, it overrides the file's)")
      ->check(CLI::IsMember({1, 2, 4}));
  sub->add_option(
         "--material-buffers", o->material_buffers,
         "material buffers: 2 loads a MATERIAL, and a per-material TABLE (a per-exponent LUT's\n"
         "reload), into the bank no span in flight reads, so neither drains the datapath;\n"
         "default 1, or the --config file's; given, it overrides the file's")
      ->check(CLI::IsMember({1, 2}));
  sub->add_option("--seed", o->seed, "stimulus seed")->capture_default_str();
  add_stimulus_options(sub, o->gap_pct, o->max_gap, o->stall_pct);
  sub->add_option("--json", o->json_path, "write the figures as JSON")->check(output_file());
  sub->add_flag(
      "--clocked", o->clocked,
      "also run the clocked cycle model when there are no gaps or back-pressure, and fail if the\n"
      "closed form disagrees with it (with gaps or back-pressure it is the only one that runs)");
  sub->add_option("--worst", o->worst, "setup-bound triangles to list, worst first")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  add_width_options(*sub, o->widths);
  add_config_option(*sub, o->config_path, {"--specular", "--channels", "--lights"});
  sub->callback([o, &exit_code]() { exit_code = run_cycles(*o); });
}

}  // namespace shadesim
