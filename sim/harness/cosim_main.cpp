// rtl_cosim_cpp / rtl_cosim_sc / rtl_cosim_cpp_trace: co-simulate the Verilated shade_unit
// against the bit-accurate model (every pixel) and the cycle model (every scanline's completion
// cycle).
//
//   rtl_cosim_cpp --config grey_s428w --scenario all --seed 1 --runs 3
//   rtl_cosim_cpp --config grey_s428w --stream failing.cmds --seed 5 --gap-pct 30 ...  (replay)
//   rtl_cosim_cpp --config grey_s428w --stream s.cmds --json result.json
//   rtl_cosim_cpp_trace --config fault_lsb --scenario mixed --waves fail.fst
//   rtl_cosim_cpp --list [--json]
//
// Exit status: 0 every run passed (or the expected mismatch was found), 1 a mismatch, 2 bad
// input (unknown configuration, unreadable or incompatible stream, bad option).
//
// --json FILE: one object per run (an array when there is more than one run):
//   {config, backend, traced, scenario, seed, stimulus: {gap_pct, max_gap, stall_pct}, passed,
//    cycles, pixels, scanlines, seconds, cycles_per_second,
//    first_mismatch: null | {kind, scanline, y, x, expected, got, cycle, message},
//    saved_stream: null | path, replay: null | command line, waves: null | {path, first_cycle, last_cycle}}
// On bad input (exit 2) the file holds {"passed": false, "error": message} when it can be written.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
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
#ifdef SHADESIM_COSIM_TRACE
#define SHADESIM_EXE "rtl_cosim_cpp_trace"
#else
#define SHADESIM_EXE "rtl_cosim_cpp"
#endif
#endif

namespace shadesim {
namespace {

#ifdef SHADESIM_COSIM_TRACE
constexpr bool kTraced = true;
#else
constexpr bool kTraced = false;
#endif

// Bad input: exit status 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Entry {
  RtlConfig config;
  std::function<CosimResult(const CosimJob&, const WaveWindow*)> run;
};

std::vector<Entry> registry() {
  std::vector<Entry> entries;
#ifdef SHADESIM_COSIM_SYSTEMC
#define SHADESIM_RUN(V, job, waves)                                                                  \
  (waves ? throw InputError("waveforms need the trace-enabled C++ build (rtl_cosim_cpp_trace)")    \
         : run_verilated_systemc<V>(job))
#else
#define SHADESIM_RUN(V, job, waves) run_verilated_cpp<V>(job, waves)
#endif
#define X(name, channels, lights, xy_bits, coef, series, spec_colour, out_bits, specular, spec_out, \
          fault_lsb, fault_stall, port_words, tri_queue, unit_params)                              \
  entries.push_back({make_rtl_config(#name, channels, lights, xy_bits, coef, series, spec_colour,     \
                                     out_bits, specular, spec_out, fault_lsb, fault_stall,            \
                                     unit_params, port_words, tri_queue),                             \
                     [](const CosimJob& job, const WaveWindow* waves) { return SHADESIM_RUN(V##name, job, waves); }});
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
  std::string json_path;
  std::string waves_path;
  uint64_t waves_before = 200, waves_after = 16;
  double min_spec_pct = 0;
  bool list = false;
};

std::string fault_text(const RtlConfig& c) {
  std::string s;
  if (c.fault_lsb_row >= 0) s += " fault=lsb@y" + std::to_string(c.fault_lsb_row);
  if (c.fault_stall_row >= 0) s += " fault=stall@y" + std::to_string(c.fault_stall_row);
  return s;
}

nlohmann::json faults_json(const RtlConfig& c) {
  nlohmann::json f = nlohmann::json::object();
  if (c.fault_lsb_row >= 0) f["lsb_row"] = c.fault_lsb_row;
  if (c.fault_stall_row >= 0) f["stall_row"] = c.fault_stall_row;
  return f;
}

// One line naming everything needed to find the mismatch.
std::string mismatch_message(const Mismatch& m, const RtlConfig& c) {
  std::ostringstream os;
  os << to_string(m.kind) << " mismatch in configuration " << c.name << " [" << c.unit.to_string()
     << fault_text(c) << "]: scanline " << m.scanline << " (y=" << m.y << "), x=" << m.x << ", cycle "
     << m.cycle << ": expected " << m.expected << ", got " << m.got;
  return os.str();
}

void write_json(const std::string& path, const nlohmann::json& j) {
  std::ofstream os(path);
  if (!os) throw InputError("--json " + path + ": cannot open for writing");
  os << j.dump(2) << '\n';
  if (!os) throw InputError("--json " + path + ": write failed");
}

struct Outcome {
  CosimJob job;
  CosimResult result;
  int64_t spec_affected = -1;  // pixels the specular term changes (-1: ideal unit, not counted)
  std::string saved_stream, replay;
  WaveWindow waves;  // path empty: none written
};

nlohmann::json outcome_json(const Outcome& o) {
  const CosimResult& r = o.result;
  const Stimulus& s = o.job.stim;
  nlohmann::json j;
  j["config"] = o.job.config.name;
  j["backend"] = SHADESIM_BACKEND;
  j["traced"] = kTraced;
  j["scenario"] = o.job.scenario;
  j["seed"] = s.seed;
  j["stimulus"] = {{"gap_pct", s.gap_pct}, {"max_gap", s.max_gap}, {"stall_pct", s.stall_pct}};
  j["passed"] = r.passed();
  j["cycles"] = r.cycles;
  j["pixels"] = r.pixels;
  j["scanlines"] = r.scanlines;
  j["seconds"] = r.seconds;
  j["cycles_per_second"] = r.seconds > 0 ? static_cast<double>(r.cycles) / r.seconds : 0.0;
  j["spec_affected_pixels"] = o.spec_affected >= 0 ? nlohmann::json(o.spec_affected) : nlohmann::json(nullptr);
  if (r.passed()) {
    j["first_mismatch"] = nullptr;
  } else {
    const Mismatch& m = r.first;
    j["first_mismatch"] = {{"kind", to_string(m.kind)}, {"scanline", m.scanline}, {"y", m.y}, {"x", m.x},
                           {"expected", m.expected}, {"got", m.got}, {"cycle", m.cycle},
                           {"message", mismatch_message(m, o.job.config)}};
  }
  j["saved_stream"] = o.saved_stream.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.saved_stream);
  j["replay"] = o.replay.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.replay);
  if (o.waves.path.empty()) {
    j["waves"] = nullptr;
  } else {
    j["waves"] = {{"path", o.waves.path}, {"first_cycle", o.waves.first}, {"last_cycle", o.waves.last}};
  }
  return j;
}

std::vector<CosimJob> make_jobs(const Options& o, const Entry& entry) {
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
    job.config = entry.config;
    job.scenario = "replay";
    try {
      job.stream = CommandStream::load(o.stream_path);
      job.stream.validate(o.stream_path);
    } catch (const std::exception& e) {
      throw InputError(e.what());
    }
    if (config_to_json(job.stream.config) != config_to_json(entry.config.unit)) {
      throw InputError(o.stream_path + ": stream configuration " + job.stream.config.to_string() +
                       " differs from --config " + entry.config.name + " (" + entry.config.unit.to_string() + ")");
    }
    job.stim = apply_overrides(Stimulus{}, o.seed);
    jobs.push_back(job);
    return jobs;
  }
  std::vector<std::string> names;
  try {
    names = o.scenario == "all" ? scenario_names() : std::vector<std::string>{o.scenario};
    for (const auto& name : names) scenario_by_name(name);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("--scenario: ") + e.what());
  }
  for (const auto& name : names) {
    Scenario sc = scenario_by_name(name);
    if (o.rows > 0) sc.shape.rows = o.rows;
    for (int k = 0; k < o.runs; ++k) {
      CosimJob job;
      job.config = entry.config;
      job.scenario = name;
      const uint64_t seed = o.seed + static_cast<uint64_t>(k);
      job.stream = random_stream(entry.config.unit, sc.shape, seed);
      job.stim = apply_overrides(sc.stim, seed);
      jobs.push_back(job);
    }
  }
  return jobs;
}

int run_all(const Options& o) {
  const std::vector<Entry> entries = registry();
  const Entry* entry = nullptr;
  for (const auto& e : entries) if (e.config.name == o.config) entry = &e;
  if (!entry) {
    std::string names;
    for (const auto& e : entries) names += (names.empty() ? "" : ", ") + e.config.name;
    throw InputError("--config '" + o.config + "' is not Verilated into this executable; expected one of " + names);
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
      throw InputError("--expect-mismatch '" + o.expect + "': expected KIND:Y, e.g. pixel:17");
    }
    if (expect_kind != "pixel" && expect_kind != "cycle") {
      throw InputError("--expect-mismatch kind '" + expect_kind + "': expected pixel or cycle");
    }
  }
  if (!o.waves_path.empty() && !kTraced) {
    throw InputError("--waves needs the trace-enabled build: run rtl_cosim_cpp_trace with the same arguments");
  }

  const std::vector<CosimJob> jobs = make_jobs(o, *entry);
#ifdef SHADESIM_COSIM_SYSTEMC
  if (jobs.size() != 1) {
    throw InputError("the SystemC kernel elaborates once per process, so this backend runs one job; got " +
                     std::to_string(jobs.size()) + " (use one --scenario and --runs 1)");
  }
#endif
  if (!o.waves_path.empty() && jobs.size() != 1) {
    throw InputError("--waves writes one file: run one job (one --scenario or --stream, --runs 1); got " +
                     std::to_string(jobs.size()));
  }

  std::vector<Outcome> outcomes;
  int failures = 0;
  int status = -1;  // set by --expect-mismatch
  for (const auto& job : jobs) {
    Outcome out;
    out.job = job;
    out.result = entry->run(job, nullptr);
    const CosimResult& r = out.result;
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
    if (job.config.unit.specular.kind != SpecularUnitKind::kIdeal) {
      const Prepared prep = prepare(job);
      out.spec_affected = static_cast<int64_t>(specular_affected_pixels(job, prep.expected));
      const double pct = prep.expected.empty() ? 0.0 : 100.0 * static_cast<double>(out.spec_affected) /
                                                           static_cast<double>(prep.expected.size());
      std::printf("  specular term changes %lld of %zu pixels (%.1f%%)\n", static_cast<long long>(out.spec_affected),
                  prep.expected.size(), pct);
      if (pct < o.min_spec_pct) {
        std::printf("  FAIL: fewer than --min-spec-pct %.1f%% of the pixels exercise the specular unit\n", o.min_spec_pct);
        ++failures;
      }
    }
    if (!r.passed()) {
      ++failures;
      const Mismatch& m = r.first;
      std::filesystem::create_directories(o.save_dir);
      out.saved_stream = o.save_dir + "/" + job.config.name + "_" + job.scenario + "_" +
                         std::to_string(job.stim.seed) + ".cmds";
      job.stream.save(out.saved_stream);
      out.replay = std::string(SHADESIM_EXE) + " --config " + job.config.name + " --stream " + out.saved_stream +
                   ' ' + job.stim.to_args();
      std::cout << "  first mismatch (" << to_string(m.kind) << "): configuration " << job.config.name
                << " [" << job.config.unit.to_string() << fault_text(job.config) << "]\n"
                << "    scanline " << m.scanline << " (y=" << m.y << "), x=" << m.x << ", cycle " << m.cycle << '\n'
                << "    expected " << m.expected << '\n'
                << "    got      " << m.got << '\n'
                << "    stream saved to " << out.saved_stream << '\n'
                << "    replay: " << out.replay << '\n';
      if (!o.waves_path.empty()) {
        // Same job again (deterministic), dumping only the window around the mismatch.
        WaveWindow w;
        w.path = o.waves_path;
        w.first = m.cycle > o.waves_before ? m.cycle - o.waves_before : 0;
        w.last = m.cycle + o.waves_after;
        const std::filesystem::path parent = std::filesystem::path(w.path).parent_path();
        if (!parent.empty()) std::filesystem::create_directories(parent);
        const CosimResult again = entry->run(job, &w);
        if (again.first.kind != m.kind || again.first.cycle != m.cycle) {
          std::cout << "    WARNING: the traced re-run mismatched differently (" << to_string(again.first.kind)
                    << " at cycle " << again.first.cycle << ")\n";
        }
        out.waves = w;
        std::cout << "    waves: " << w.path << " (cycles " << w.first << ".." << w.last << ", time = "
                  << kWaveUnitsPerCycle << " x (cycle + " << kResetCycles << "))\n";
      }
      if (!expect_kind.empty() && status < 0) {
        const bool as_expected = to_string(m.kind) == expect_kind && m.y == expect_y;
        std::cout << (as_expected ? "  the deliberate fault was caught where expected\n"
                                  : "  FAIL: expected the first mismatch to be " + o.expect + "\n");
        status = as_expected ? 0 : 1;
      }
    }
    outcomes.push_back(out);
    if (status >= 0) break;
  }
  if (!o.json_path.empty()) {
    nlohmann::json j;
    if (outcomes.size() == 1) {
      j = outcome_json(outcomes.front());
    } else {
      j = nlohmann::json::array();
      for (const auto& out : outcomes) j.push_back(outcome_json(out));
    }
    write_json(o.json_path, j);
  }
  if (!expect_kind.empty()) {
    if (status < 0) {
      std::cout << "FAIL: expected a mismatch (" << o.expect << "), but every run passed\n";
      return 1;
    }
    return status;
  }
  return failures == 0 ? 0 : 1;
}

void print_list(bool json) {
  const std::vector<Entry> entries = registry();
  if (!json) {
    for (const auto& e : entries) std::cout << e.config.name << "  " << e.config.unit.to_string() << fault_text(e.config) << '\n';
    return;
  }
  nlohmann::json all = nlohmann::json::array();
  for (const auto& e : entries) {
    all.push_back({{"name", e.config.name},
                   {"unit", nlohmann::json::parse(config_to_json(e.config.unit))},
                   {"faults", faults_json(e.config)}});
  }
  std::cout << all.dump(2) << '\n';
}

int cosim_main(int argc, char** argv) {
  CLI::App app{"Co-simulate the Verilated shade_unit (" SHADESIM_BACKEND
               " backend) against the bit-accurate model and the cycle model"};
  Options o;
  bool list_json = false;
  app.add_option("--config", o.config, "RTL configuration (see --list)");
  app.add_flag("--list", o.list, "list the Verilated configurations (with --json: as JSON on stdout)");
  app.add_option("--scenario", o.scenario, "mixed, long, short, slow, maxbp, switch, tiny, or all");
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
  auto* json_opt = app.add_option("--json", o.json_path, "write each run's result as JSON to this file")
                       ->expected(0, 1);
  app.add_option("--waves", o.waves_path,
                 "on a mismatch, re-run with tracing and write an FST of the cycles around it (rtl_cosim_cpp_trace)");
  app.add_option("--min-spec-pct", o.min_spec_pct,
                 "fail a run where the specular term changes fewer than this percentage of the pixels")
      ->check(CLI::Range(0.0, 100.0));
  app.add_option("--waves-before", o.waves_before, "cycles before the mismatch in the waveform")->capture_default_str();
  app.add_option("--waves-after", o.waves_after, "cycles after the mismatch in the waveform")->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  list_json = json_opt->count() > 0;
  if (o.list) {
    if (list_json && !o.json_path.empty()) {
      std::cerr << SHADESIM_EXE ": error: --list --json prints to stdout; it takes no file name\n";
      return 2;
    }
    print_list(list_json);
    return 0;
  }
  if (list_json && o.json_path.empty()) {
    std::cerr << SHADESIM_EXE ": error: --json needs a file name (only --list --json prints to stdout)\n";
    return 2;
  }
  try {
    return run_all(o);
  } catch (const std::exception& e) {  // InputError, or a file the run could not write
    std::cerr << SHADESIM_EXE ": error: " << e.what() << '\n';
    if (!o.json_path.empty()) {
      std::ofstream os(o.json_path);
      if (os) os << nlohmann::json{{"passed", false}, {"error", e.what()}}.dump(2) << '\n';
    }
    return 2;
  }
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
