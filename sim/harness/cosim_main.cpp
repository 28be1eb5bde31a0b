// rtl_cosim_cpp / rtl_cosim_sc: co-simulate the Verilated shade_unit against the bit-accurate
// model (every pixel) and the cycle model (every scanline's completion cycle).
//
//   rtl_cosim_cpp --config grey_s428w --scenario all --seed 1 --runs 3
//   rtl_cosim_cpp --config grey_s428w --stream failing.cmds --seed 5 --gap-pct 30 ...  (replay)
//   rtl_cosim_cpp --list
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <sstream>

#include "rtl_configs.inc"
#include "sim/harness/cosim.h"
#include "sim/harness/random_stream.h"

#ifdef SHADESIM_COSIM_SYSTEMC
#include "sim/harness/sc_backend.h"
#define SHADESIM_BACKEND "systemc"
#define SHADESIM_EXE "rtl_cosim_sc"
#else
#include "sim/harness/cpp_backend.h"
#define SHADESIM_BACKEND "cpp"
#define SHADESIM_EXE "rtl_cosim_cpp"
#endif

namespace shadesim {
namespace {

struct Entry {
  RtlConfig config;
  std::function<CosimResult(const CosimJob&)> run;
};

std::vector<Entry> registry() {
  std::vector<Entry> entries;
#ifdef SHADESIM_COSIM_SYSTEMC
#define SHADESIM_RUN(V) run_verilated_systemc<V>
#else
#define SHADESIM_RUN(V) run_verilated_cpp<V>
#endif
#define X(name, channels, lights, xy_bits, coef, series, spec_colour, out_bits, specular, spec_out, \
          fault_lsb, fault_stall)                                                                  \
  entries.push_back({make_rtl_config(#name, channels, lights, xy_bits, coef, series, spec_colour,     \
                                     out_bits, specular, spec_out, fault_lsb, fault_stall),           \
                     [](const CosimJob& job) { return SHADESIM_RUN(V##name)(job); }});
  SHADESIM_RTL_CONFIGS(X)
#undef X
  return entries;
}

struct Options {
  std::string config;
  std::string scenario = "mixed";
  std::string stream_path;
  uint64_t seed = 1;
  int runs = 1;
  int rows = 0;  // 0: the scenario's own
  int gap_pct = -1, max_gap = -1, stall_pct = -1;
  std::string expect;  // KIND:Y
  std::string save_dir = ".";
  bool list = false;
};

std::string fault_text(const RtlConfig& c) {
  std::string s;
  if (c.fault_lsb_row >= 0) s += " fault=lsb@y" + std::to_string(c.fault_lsb_row);
  if (c.fault_stall_row >= 0) s += " fault=stall@y" + std::to_string(c.fault_stall_row);
  return s;
}

int cosim_main(int argc, char** argv) {
  CLI::App app{"Co-simulate the Verilated shade_unit (" SHADESIM_BACKEND
               " backend) against the bit-accurate model and the cycle model"};
  Options o;
  app.add_option("--config", o.config, "RTL configuration (see --list)");
  app.add_flag("--list", o.list, "list the Verilated configurations");
  app.add_option("--scenario", o.scenario, "mixed, long, short, slow, maxbp, switch, or all");
  app.add_option("--stream", o.stream_path, "replay a saved command stream (text form)");
  app.add_option("--seed", o.seed, "seed of the stream and of the stimulus (printed on every run)");
  app.add_option("--rows", o.rows, "override: scanlines per generated stream (for benchmarks)")->check(CLI::Range(1, 32768));
  app.add_option("--runs", o.runs, "consecutive seeds per scenario")->check(CLI::PositiveNumber);
  app.add_option("--gap-pct", o.gap_pct, "override: chance of idle cycles before a command word")->check(CLI::Range(0, 100));
  app.add_option("--max-gap", o.max_gap, "override: longest idle gap")->check(CLI::Range(1, 100000));
  app.add_option("--stall-pct", o.stall_pct, "override: chance of pix_ready low per cycle")->check(CLI::Range(0, 99));
  app.add_option("--expect-mismatch", o.expect,
                 "KIND:Y - succeed only if the first mismatch is KIND (pixel|cycle) at scanline y=Y");
  app.add_option("--save-dir", o.save_dir, "where a failing run's command stream is saved");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  const std::vector<Entry> entries = registry();
  if (o.list) {
    for (const auto& e : entries) std::cout << e.config.name << "  " << e.config.unit.to_string() << fault_text(e.config) << '\n';
    return 0;
  }
  const Entry* entry = nullptr;
  for (const auto& e : entries) if (e.config.name == o.config) entry = &e;
  if (!entry) {
    std::string names;
    for (const auto& e : entries) names += (names.empty() ? "" : ", ") + e.config.name;
    std::cerr << SHADESIM_EXE ": error: --config '" << o.config << "' is not Verilated into this executable; expected one of " << names << '\n';
    return 2;
  }
  std::string expect_kind;
  int expect_y = -1;
  if (!o.expect.empty()) {
    const auto colon = o.expect.find(':');
    try {
      if (colon == std::string::npos) throw std::invalid_argument(o.expect);
      expect_kind = o.expect.substr(0, colon);
      expect_y = std::stoi(o.expect.substr(colon + 1));
    } catch (const std::logic_error&) {
      std::cerr << SHADESIM_EXE ": error: --expect-mismatch '" << o.expect << "': expected KIND:Y, e.g. pixel:17\n";
      return 2;
    }
    if (expect_kind != "pixel" && expect_kind != "cycle") {
      std::cerr << SHADESIM_EXE ": error: --expect-mismatch kind '" << expect_kind << "': expected pixel or cycle\n";
      return 2;
    }
  }

  // The jobs: scenarios x seeds, or one replayed stream.
  std::vector<CosimJob> jobs;
  auto apply_overrides = [&o](Stimulus s, uint64_t seed) {
    s.seed = seed;
    if (o.gap_pct >= 0) s.gap_pct = o.gap_pct;
    if (o.max_gap >= 0) s.max_gap = o.max_gap;
    if (o.stall_pct >= 0) s.stall_pct = o.stall_pct;
    return s;
  };
  if (!o.stream_path.empty()) {
    CosimJob job;
    job.config = entry->config;
    job.scenario = "replay";
    job.stream = CommandStream::load(o.stream_path);
    job.stream.validate(o.stream_path);
    if (config_to_json(job.stream.config) != config_to_json(entry->config.unit)) {
      std::cerr << SHADESIM_EXE ": error: " << o.stream_path << ": stream configuration "
                << job.stream.config.to_string() << " differs from --config " << entry->config.name
                << " (" << entry->config.unit.to_string() << ")\n";
      return 2;
    }
    job.stim = apply_overrides(Stimulus{}, o.seed);
    jobs.push_back(job);
  } else {
    const std::vector<std::string> names =
        o.scenario == "all" ? scenario_names() : std::vector<std::string>{o.scenario};
    for (const auto& name : names) {
      Scenario sc = scenario_by_name(name);
      if (o.rows > 0) sc.shape.rows = o.rows;
      for (int k = 0; k < o.runs; ++k) {
        CosimJob job;
        job.config = entry->config;
        job.scenario = name;
        const uint64_t seed = o.seed + static_cast<uint64_t>(k);
        job.stream = random_stream(entry->config.unit, sc.shape, seed);
        job.stim = apply_overrides(sc.stim, seed);
        jobs.push_back(job);
      }
    }
  }
#ifdef SHADESIM_COSIM_SYSTEMC
  if (jobs.size() != 1) {
    std::cerr << SHADESIM_EXE ": error: the SystemC kernel elaborates once per process, so this "
                 "backend runs one job; got " << jobs.size() << " (use one --scenario and --runs 1)\n";
    return 2;
  }
#endif

  int failures = 0;
  for (const auto& job : jobs) {
    const CosimResult r = entry->run(job);
    char line[512];
    std::snprintf(line, sizeof line,
                  "%-8s %-12s %-7s seed=%-6llu pixels=%-7llu scanlines=%-5llu cycles=%-8llu "
                  "cyc/px=%.3f wall=%.3fs %.2f Mcycles/s  %s",
                  SHADESIM_BACKEND, job.config.name.c_str(), job.scenario.c_str(),
                  static_cast<unsigned long long>(job.stim.seed), static_cast<unsigned long long>(r.pixels),
                  static_cast<unsigned long long>(r.scanlines), static_cast<unsigned long long>(r.cycles),
                  r.pixels ? static_cast<double>(r.cycles) / static_cast<double>(r.pixels) : 0.0, r.seconds,
                  r.seconds > 0 ? static_cast<double>(r.cycles) / r.seconds / 1e6 : 0.0,
                  r.passed() ? "PASS" : "MISMATCH");
    std::cout << line << '\n';
    if (r.passed()) continue;
    ++failures;
    const Mismatch& m = r.first;
    std::filesystem::create_directories(o.save_dir);
    const std::string path = o.save_dir + "/" + job.config.name + "_" + job.scenario + "_" +
                             std::to_string(job.stim.seed) + ".cmds";
    job.stream.save(path);
    std::cout << "  first mismatch (" << to_string(m.kind) << "): configuration " << job.config.name
              << " [" << job.config.unit.to_string() << fault_text(job.config) << "]\n"
              << "    scanline " << m.scanline << " (y=" << m.y << "), x=" << m.x << ", cycle " << m.cycle << '\n'
              << "    expected " << m.expected << '\n'
              << "    got      " << m.got << '\n'
              << "    stream saved to " << path << '\n'
              << "    replay: " << SHADESIM_EXE << " --config " << job.config.name << " --stream " << path
              << ' ' << job.stim.to_args() << '\n';
    if (!expect_kind.empty()) {
      const bool as_expected = to_string(m.kind) == expect_kind && m.y == expect_y;
      std::cout << (as_expected ? "  the deliberate fault was caught where expected\n"
                                : "  FAIL: expected the first mismatch to be " + o.expect + "\n");
      return as_expected ? 0 : 1;
    }
  }
  if (!expect_kind.empty()) {
    std::cout << "FAIL: expected a mismatch (" << o.expect << "), but every run passed\n";
    return 1;
  }
  return failures == 0 ? 0 : 1;
}

}  // namespace
}  // namespace shadesim

#ifdef SHADESIM_COSIM_SYSTEMC
int sc_main(int argc, char** argv) {
  try {
    return shadesim::cosim_main(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << SHADESIM_EXE ": error: " << e.what() << '\n';
    return 2;
  }
}
#else
int main(int argc, char** argv) {
  try {
    return shadesim::cosim_main(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << SHADESIM_EXE ": error: " << e.what() << '\n';
    return 2;
  }
}
#endif
