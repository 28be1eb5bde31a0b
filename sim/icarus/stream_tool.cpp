// icarus_stream_tool: the files the Icarus testbench (sim/icarus/tb_shade_unit.sv) reads and
// the check of what it writes.
//
//   icarus_stream_tool export STREAM.cmds --hex WORDS.hex --pixels EXPECTED.txt
//                     [--gaps GAPS.hex --cycles CYCLES.hex --seed S --gap-pct G --max-gap M
//                     --stall-pct P]
//       the stream's binary words for $readmemh (a first line "// shadesim-words N ...", then
//       one 16-digit hex word per line) and the bit-accurate model's pixels (ShadeUnit), one
//       "x y c0 [c1 c2] eor cycle" line each, decimal, `cycle` being the one on which the cycle
//       model (the harness's cycle oracle) lets the pixel's beat leave under that stimulus.
//       --gaps / --cycles: the Verilator harness's stimulus (sim/harness/stimulus.h, the same
//       options and defaults as `shadesim cosim --stream`) as the testbench's schedule, so that it
//       drives the same inputs on the same cycles instead of a Verilog copy of the generator:
//         GAPS.hex    "// shadesim-gaps N ...", then per beat the idle cycles before it is
//                     offered (Stimulus::gap_before; CommandDriver's rule);
//         CYCLES.hex  "// shadesim-cycles N ...", then per cycle from 0 "R NOISE": pix_ready
//                     (Stimulus::pix_ready) and the port's PORT_WORDS idle-noise words, last word
//                     first (sim/harness/idle_noise.h), driven while cmd_valid is low. N is the
//                     harness's own bound (cosim.h prepare: the cycle model's cycles + 1000);
//                     a run that gets past it is late or hung, as in the harness.
//   icarus_stream_tool random --builds sim/harness/builds.json --config NAME --scenario mixed
//   --seed 1 --save OUT.cmds
//       a co-simulation random stream (sim/harness/random_stream.h) for a named build; prints
//       the scenario's stimulus ("stimulus: --seed S --gap-pct G --max-gap M --stall-pct P"),
//       the options export and `shadesim cosim` take;
//   icarus_stream_tool compare EXPECTED.txt GOT.txt
//       bit-for-bit comparison of two pixel files; the first difference is described.
#include <CLI/CLI.hpp>
#include <array>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/command_stream.h"
#include "model/cycle_model.h"
#include "model/shade_unit.h"
#include "sim/harness/cosim.h"
#include "sim/harness/idle_noise.h"
#include "sim/harness/random_stream.h"
#include "sim/harness/rtl_config.h"
#include "sim/harness/stimulus.h"

namespace shadesim {
namespace {

class ToolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::ofstream open_out(const std::string& path) {
  std::ofstream os(path);
  if (!os) throw ToolError(path + ": cannot open for writing");
  return os;
}

// The cycle on which each of the model's pixels leaves, as the cycle model clocks the stream
// under `stim` (the loop of the harness's lockstep model: sim/harness/cpp_backend.cpp). Each beat
// holds pix_count pixels from lane 0's x; they must be the model's next pixels.
std::vector<uint64_t> pixel_exit_cycles(const std::vector<uint64_t>& words, const Stimulus& stim,
                                        const UnitConfig& cfg, const std::vector<PixelOut>& pixels,
                                        uint64_t cycle_limit) {
  CycleModel model(CycleConfig::of(cfg));
  CommandDriver driver(words, stim, cfg.port_words);
  std::vector<uint64_t> exit;
  exit.reserve(pixels.size());
  for (uint64_t cycle = 0; exit.size() < pixels.size(); ++cycle) {
    if (cycle > cycle_limit) {
      throw ToolError("the cycle model let " + std::to_string(exit.size()) + " of " +
                      std::to_string(pixels.size()) + " pixels out by its own cycle bound " +
                      std::to_string(cycle_limit));
    }
    const CycleModel::Edge e = model.clock(driver.valid(), driver.beat(), stim.pix_ready(cycle));
    driver.clock(e.cmd_fire);
    if (!e.pix_fire) continue;
    for (int j = 0; j < e.pix_count; ++j) {
      const size_t i = exit.size();
      if (i >= pixels.size() || pixels[i].x != e.pix_x + j || pixels[i].y != e.pix_y) {
        throw ToolError("the cycle model's beat on cycle " + std::to_string(cycle) +
                        " holds pixel (" + std::to_string(e.pix_x + j) + ", " +
                        std::to_string(e.pix_y) + "), not the bit-accurate model's pixel " +
                        std::to_string(i));
      }
      exit.push_back(cycle);
    }
  }
  return exit;
}

std::string header_tail(const std::string& stream_path, const CommandStream& stream,
                        const Stimulus& stim) {
  return stream_path + ": " + stream.config.to_string() + " " + stim.to_args();
}

// Per beat, the idle cycles before it is offered.
void write_gaps(const std::string& path, size_t beats, const Stimulus& stim,
                const std::string& tail) {
  std::ofstream os = open_out(path);
  os << "// shadesim-gaps " << beats << ' ' << tail << '\n';
  char line[20];
  for (size_t i = 0; i < beats; ++i) {
    std::snprintf(line, sizeof line, "%x\n", static_cast<unsigned>(stim.gap_before(i)));
    os << line;
  }
  if (!os) throw ToolError(path + ": write failed");
}

// Per cycle 0 .. n-1, pix_ready and the idle noise on the port's words.
void write_cycles(const std::string& path, uint64_t n, int port_words, const Stimulus& stim,
                  const std::string& tail) {
  std::ofstream os = open_out(path);
  os << "// shadesim-cycles " << n << ' ' << tail << '\n';
  char word[20];
  for (uint64_t c = 0; c < n; ++c) {
    const std::array<uint64_t, 8> noise = idle_noise(stim, c);
    os << (stim.pix_ready(c) ? '1' : '0') << ' ';
    for (int k = port_words - 1; k >= 0; --k) {
      std::snprintf(word, sizeof word, "%016llx",
                    static_cast<unsigned long long>(noise[static_cast<size_t>(k)]));
      os << word;
    }
    os << '\n';
  }
  if (!os) throw ToolError(path + ": write failed");
}

struct ExportFiles {
  std::string hex, pixels, gaps, cycles;
};

void export_stream(const std::string& stream_path, const ExportFiles& out, const Stimulus& stim) {
  const CommandStream stream = CommandStream::load(stream_path);
  stream.validate(stream_path);
  CosimJob job;
  job.config.unit = stream.config;
  job.stream = stream;
  job.stim = stim;
  const Prepared prep =
      prepare(job);  // the words, the model's pixels and the harness's cycle bound
  const std::string tail = header_tail(stream_path, stream, stim);
  if (!out.hex.empty()) {
    std::ofstream os = open_out(out.hex);
    // $readmemh skips // comments; the testbench reads the count from this first line.
    os << "// shadesim-words " << prep.words.size() << ' ' << tail << '\n';
    char word[20];
    for (uint64_t w : prep.words) {
      std::snprintf(word, sizeof word, "%016llx\n", static_cast<unsigned long long>(w));
      os << word;
    }
    if (!os) throw ToolError(out.hex + ": write failed");
  }
  const int port_words = stream.config.port_words;
  if (!out.gaps.empty()) {
    write_gaps(
        out.gaps,
        (prep.words.size() + static_cast<size_t>(port_words) - 1) / static_cast<size_t>(port_words),
        stim, tail);
  }
  // The harness clocks cycles 0 .. cycle_limit before it calls the run timed out.
  if (!out.cycles.empty()) write_cycles(out.cycles, prep.cycle_limit + 1, port_words, stim, tail);
  if (!out.pixels.empty()) {
    const std::vector<uint64_t> exit =
        pixel_exit_cycles(prep.words, stim, stream.config, prep.expected, prep.cycle_limit);
    std::ofstream os = open_out(out.pixels);
    for (size_t i = 0; i < prep.expected.size(); ++i) {
      const PixelOut& p = prep.expected[i];
      os << p.x << ' ' << p.y;
      for (int c = 0; c < stream.config.channels; ++c) os << ' ' << p.colour[c];
      os << ' ' << (p.end_of_row ? 1 : 0) << ' ' << exit[i] << '\n';
    }
    if (!os) throw ToolError(out.pixels + ": write failed");
  }
}

void random_to_file(const std::string& builds, const std::string& name, const std::string& scenario,
                    uint64_t seed, const std::string& out) {
  RtlConfig rtl;
  try {
    rtl = named_build(builds, name);
  } catch (const std::invalid_argument& e) {
    throw ToolError(std::string("--config: ") + e.what());
  }
  Scenario sc = scenario_by_name(scenario);
  random_stream(rtl.unit, sc.shape, seed).save(out);
  sc.stim.seed = seed;  // as `shadesim cosim --scenario` seeds it
  std::cout << "stimulus: " << sc.stim.to_args() << '\n';
}

std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream is(path);
  if (!is) throw ToolError(path + ": cannot open");
  std::vector<std::string> lines;
  for (std::string line; std::getline(is, line);) lines.push_back(line);
  return lines;
}

// Exit status 0 when identical; otherwise the first difference goes to stderr.
int compare_pixels(const std::string& expected_path, const std::string& got_path) {
  const std::vector<std::string> expected = read_lines(expected_path);
  const std::vector<std::string> got = read_lines(got_path);
  const size_t n = std::min(expected.size(), got.size());
  for (size_t i = 0; i < n; ++i) {
    if (expected[i] != got[i]) {
      std::cerr << "pixel " << i << " (line " << i + 1 << "): expected \"" << expected[i] << "\" ("
                << expected_path << "), got \"" << got[i] << "\" (" << got_path
                << ")  [x y colour.. eor exit-cycle]\n";
      return 1;
    }
  }
  if (expected.size() != got.size()) {
    std::cerr << "pixel count: expected " << expected.size() << " (" << expected_path << "), got "
              << got.size() << " (" << got_path << "); the first " << n << " agree\n";
    return 1;
  }
  std::cout << "pixels identical: " << n << " (" << got_path << " = " << expected_path << ")\n";
  return 0;
}

int tool_main(int argc, char** argv) {
  CLI::App app{"Command-stream files for the Icarus testbench, and the check of its pixels"};
  app.require_subcommand(1);

  std::string stream_path;
  ExportFiles files;
  Stimulus stim;  // `shadesim cosim --stream`'s defaults: no gaps, no back-pressure
  CLI::App* exp = app.add_subcommand(
      "export", "hex words, stimulus schedule and the model's expected pixels of a saved stream");
  exp->add_option("stream", stream_path, "saved command stream (text form)")
      ->required()
      ->check(CLI::ExistingFile);
  exp->add_option("--hex", files.hex, "write the binary words for $readmemh");
  exp->add_option("--pixels", files.pixels,
                  "write the bit-accurate model's pixels, each with the cycle model's exit cycle");
  exp->add_option("--gaps", files.gaps,
                  "write the idle cycles before each beat (the testbench's +gaps=)");
  exp->add_option("--cycles", files.cycles,
                  "write pix_ready and the idle noise of each cycle (the testbench's +cycles=)");
  exp->add_option("--seed", stim.seed, "stimulus seed, as shadesim cosim's")->capture_default_str();
  exp->add_option("--gap-pct", stim.gap_pct, "chance of idle cycles before a beat")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  exp->add_option("--max-gap", stim.max_gap, "longest idle gap")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  exp->add_option("--stall-pct", stim.stall_pct, "chance of pix_ready low per cycle")
      ->check(CLI::Range(0, 99))
      ->capture_default_str();

  std::string builds, name, scenario = "mixed", save_path;
  uint64_t seed = 1;
  CLI::App* rnd = app.add_subcommand("random", "save a co-simulation random stream");
  rnd->add_option("--builds", builds, "the named builds file (sim/harness/builds.json)")
      ->required();
  rnd->add_option("--config", name, "a named build")->required();
  rnd->add_option("--scenario", scenario, "mixed, long, short, slow, maxbp, switch, tiny, edge")
      ->capture_default_str();
  rnd->add_option("--seed", seed, "stream seed")->capture_default_str();
  rnd->add_option("--save", save_path, "output stream (text form)")->required();

  std::string expected_path, got_path;
  CLI::App* cmp = app.add_subcommand("compare", "compare two pixel files bit for bit");
  cmp->add_option("expected", expected_path, "expected pixels (export --pixels)")->required();
  cmp->add_option("got", got_path, "pixels written by the testbench")->required();

  std::string fault_text;
  CLI::App* plus = app.add_subcommand(
      "fault-plusargs", "the testbench's plusargs that inject a deliberate fault (SITE@Y)");
  plus->add_option("fault", fault_text, "SITE@Y, as shadesim cosim --fault takes it")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (*plus) {
    std::string line;
    for (const std::string& a : parse_fault(fault_text).plusargs())
      line += (line.empty() ? "" : " ") + a;
    std::cout << line << '\n';
    return 0;
  }
  if (*exp) {
    if (files.hex.empty() && files.pixels.empty() && files.gaps.empty() && files.cycles.empty()) {
      throw ToolError("export: give --hex, --pixels, --gaps and/or --cycles");
    }
    export_stream(stream_path, files, stim);
    return 0;
  }
  if (*rnd) {
    random_to_file(builds, name, scenario, seed, save_path);
    return 0;
  }
  return compare_pixels(expected_path, got_path);
}

}  // namespace
}  // namespace shadesim

int main(int argc, char** argv) {
  try {
    return shadesim::tool_main(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "icarus_stream_tool: error: " << e.what() << '\n';
    return 2;
  }
}
