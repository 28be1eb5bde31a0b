// shadesim cycles SCENE: cycles per pixel from the cycle model alone — the timing of
// rtl/shade_unit.sv without its datapath, exact to the cycle (co-simulation checks it against
// the RTL on every scanline) and far faster than simulating the RTL.
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "host/frame.h"
#include "model/cycle_model.h"
#include "sim/commands.h"
#include "model/coef_packing.h"
#include "sim/config_option.h"
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
  uint64_t seed = 1;
  int gap_pct = 0, max_gap = 1, stall_pct = 0;
  std::string json_path;
  std::string config_path;  // --config: the unit is exactly this file's
};

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
  const double host_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  Stimulus stim;
  stim.seed = o.seed;
  stim.gap_pct = o.gap_pct;
  stim.max_gap = o.max_gap;
  stim.stall_pct = o.stall_pct;
  const CycleConfig unit_timing = CycleConfig::of(frame.config);
  const SlotTiming& timing = unit_timing.slot;
  const std::vector<uint64_t> words = frame.encoded.stream.encode();
  const auto t1 = std::chrono::steady_clock::now();
  const CycleRun run = CycleModel::run(words, stim, unit_timing);
  const double model_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  // What the triangle queue hid: the same stream and stimulus on the same unit with one bank.
  CycleConfig one_bank = unit_timing;
  one_bank.tri_queue = 1;
  const uint64_t cycles_one_bank =
      unit_timing.tri_queue > 1 ? CycleModel::run(words, stim, one_bank).cycles : run.cycles;
  const int64_t queue_hid = static_cast<int64_t>(cycles_one_bank) - static_cast<int64_t>(run.cycles);
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

  const double cpp = run.pixels ? static_cast<double>(run.cycles) / static_cast<double>(run.pixels) : 0.0;
  std::cout << "scene        " << o.scene << " (" << frame.scene.width << "x" << frame.scene.height << ")\n"
            << "unit         " << frame.config.to_string() << "\n"
            << "specular     " << frame.config.specular.describe() << ": latency " << timing.latency
            << ", " << timing.interval << " cycle(s) per pixel\n"
            << "command port " << unit_timing.port_words << " word(s) per beat, triangle queue "
            << unit_timing.tri_queue << " (span queue " << unit_timing.span_queue() << "), "
            << unit_timing.lanes << " pixel lane(s)\n"
            << "stimulus     seed " << o.seed << ", input gaps " << o.gap_pct << "% (max " << o.max_gap
            << "), back-pressure " << o.stall_pct << "%\n"
            << "stream       " << words.size() << " words: " << frame.encoded.stats.triangles << " tri, "
            << frame.encoded.stats.spans << " spans, " << frame.encoded.stats.materials << " material loads, "
            << frame.encoded.stats.table_words << " table words\n"
            << "triangle     " << 1 + layout.words << " words: 1 header + " << layout.words
            << " payload (one coefficient a word: " << unpacked_words << ") holding "
            << diffuse_bits + specular_bits << " coefficient bits: diffuse " << diffuse_bits << " ("
            << frame.config.diffuse_series() << " series), specular " << specular_bits << " ("
            << frame.config.specular_series() << " series); T0..T5 " << term_bits << " bits\n"
            << "pixels       " << run.pixels
            << (unit_timing.lanes > 1 ? " in " + std::to_string(run.breakdown.pixel) + " beats of up to " +
                                            std::to_string(unit_timing.lanes) + " (lanes within a span)"
                                      : std::string())
            << "\n"
            << "cycles       " << run.cycles << "  (" << std::fixed << std::setprecision(3) << cpp
            << " cycles per pixel)\n"
            << "queue        " << queue_hid << " cycles hidden by the triangle queue (tri_queue 1: "
            << cycles_one_bank << ")\n\n"
            << "breakdown    (every cycle charged to one reason; the rows sum to the total)\n";
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& r : run.breakdown.rows()) {
    const double pct = run.cycles ? 100.0 * static_cast<double>(r.cycles) / static_cast<double>(run.cycles) : 0.0;
    std::cout << "  " << std::left << std::setw(15) << r.name << std::right << std::setw(12) << r.cycles
              << std::setw(8) << std::setprecision(1) << pct << " %  " << r.meaning << '\n';
    rows.push_back({{"name", r.name}, {"cycles", r.cycles}, {"percent", pct}, {"meaning", r.meaning}});
  }
  std::cout << "\ntime         host " << std::setprecision(3) << host_s << " s, cycle model " << model_s << " s ("
            << std::setprecision(1) << (model_s > 0 ? static_cast<double>(run.cycles) / model_s / 1e6 : 0.0)
            << " M cycles/s)\n";
  if (!o.json_path.empty()) {
    nlohmann::json j = {{"scene", o.scene},
                        {"config", nlohmann::json::parse(config_to_json(frame.config))},
                        {"slot", {{"latency", timing.latency}, {"interval", timing.interval}}},
                        {"stimulus", {{"seed", o.seed}, {"gap_pct", o.gap_pct}, {"max_gap", o.max_gap}, {"stall_pct", o.stall_pct}}},
                        {"words", words.size()},
                        {"beats", run.beats},
                        {"triangle_words", {{"header", 1}, {"payload", layout.words},
                                            {"unpacked_payload", unpacked_words},
                                            {"total", 1 + layout.words},
                                            {"diffuse_bits", diffuse_bits}, {"specular_bits", specular_bits},
                                            {"term_bits", term_bits_json}}},
                        {"queue_hidden_cycles", queue_hid},
                        {"cycles_tri_queue_1", cycles_one_bank},
                        {"pixels", run.pixels},
                        {"pixel_beats", run.breakdown.pixel},
                        {"cycles", run.cycles},
                        {"cycles_per_pixel", cpp},
                        {"breakdown", rows},
                        {"seconds", {{"host", host_s}, {"cycle_model", model_s}}}};
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
      "Estimate cycles per pixel for a scene from the cycle model alone (the RTL's control, clock by\n"
      "clock, without its datapath: exact to the cycle, far faster than co-simulation), with a\n"
      "breakdown of where the cycles go: pixels, span setup, unit stalls, table reloads, material\n"
      "drains, command words and gaps, back-pressure.");
  sub->add_option("scene", o->scene, "scene JSON file")->required()->check(CLI::ExistingFile);
  sub->add_option("--specular", o->specular, "specular unit: ideal|lut|schlick|wpow (default: the scene's)");
  sub->add_option("--channels", o->channels, "build with this many channels (default: what the scene needs)")
      ->check(CLI::IsMember({1, 3}));
  sub->add_option("--lights", o->lights, "build with series for this many lights (default: the scene's)")
      ->check(CLI::Range(1, 8));
  sub->add_option("--port-words", o->port_words,
                  "command port width: 64-bit words per handshake (default 1, or the --config file's;\n"
                  "given, it overrides the file's)")
      ->check(CLI::IsMember({1, 2, 4, 8}));
  sub->add_option("--tri-queue", o->tri_queue,
                  "triangle queue depth: coefficient banks; > 1 adds a span queue (default 1, or the\n"
                  "--config file's; given, it overrides the file's)")
      ->check(CLI::Range(1, 8));
  sub->add_option("--lanes", o->lanes,
                  "pixel lanes: pixels of one span per clock (k-step forward differences, lane j at\n"
                  "x0 + j; default 1, or the --config file's; given, it overrides the file's)")
      ->check(CLI::IsMember({1, 2, 4}));
  sub->add_option("--seed", o->seed, "stimulus seed")->capture_default_str();
  sub->add_option("--gap-pct", o->gap_pct, "chance of idle cycles before a command word")->check(CLI::Range(0, 100))->capture_default_str();
  sub->add_option("--max-gap", o->max_gap, "longest idle gap in cycles")->check(CLI::Range(1, 100000))->capture_default_str();
  sub->add_option("--stall-pct", o->stall_pct, "chance of output back-pressure per cycle")->check(CLI::Range(0, 99))->capture_default_str();
  sub->add_option("--json", o->json_path, "write the figures as JSON");
  add_width_options(*sub, o->widths);
  add_config_option(*sub, o->config_path, {"--specular", "--channels", "--lights"});
  sub->callback([o, &exit_code]() { exit_code = run_cycles(*o); });
}

}  // namespace shadesim
