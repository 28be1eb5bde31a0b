// The co-simulation executable of one RTL build: the Verilated shade_unit (C++, SystemC, or C++
// with FST tracing) against the bit-accurate model (every pixel) and the cycle model (every
// scanline's completion cycle). shadesim builds one per parameter set into its cache
// (sim/rtl_build.h) and runs it through `shadesim cosim`, which passes the unit as a file:
//
//   <exe> --unit unit.json --config grey_s428w --scenario all --seed 1 --runs 3
//   <exe> --stream failing.cmds --seed 5 --gap-pct 30 ...   (replay: the stream names its unit)
//   <exe> --unit unit.json --stream s.cmds --json result.json
//   <exe> --unit unit.json --config fault_lsb --scenario mixed --waves fail.fst   (traced build)
//   <exe> --list [--json]
//
// The unit must map (model/rtl_parameters.h) to exactly the parameters this executable was
// Verilated with; the deliberate faults are read from those parameters.
//
// Exit status: 0 every run passed (or the expected mismatch was found), 1 a mismatch, 2 bad
// input (unit of another build, unreadable or incompatible stream, bad option).
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

#include "Vshade_unit.h"
#include "cosim_build.h"
#include "model/rtl_parameters.h"
#include "model/unit_config_file.h"
#include "sim/harness/cosim.h"
#include "sim/harness/random_stream.h"

#ifdef SHADESIM_COSIM_SYSTEMC
#include "sim/harness/sc_backend.h"
#define SHADESIM_BACKEND "systemc"
#define SHADESIM_EXE "shadesim cosim --backend systemc"
#else
#include "sim/harness/cpp_backend.h"
#define SHADESIM_BACKEND "cpp"
#ifdef SHADESIM_COSIM_TRACE
#define SHADESIM_EXE "shadesim cosim --backend cpp --waves"
#else
#define SHADESIM_EXE "shadesim cosim --backend cpp"
#endif
#endif

namespace shadesim {
namespace {

#ifdef SHADESIM_COSIM_TRACE
constexpr bool kTraced = true;
#else
constexpr bool kTraced = false;
#endif
#ifdef SHADESIM_COSIM_COVERAGE
constexpr bool kCovered = true;
#else
constexpr bool kCovered = false;
#endif

// Bad input: exit status 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The parameters this executable was Verilated with (cosim_build.h, written by sim/rtl_build.cpp).
std::vector<VerilogParameter> built_parameters() { return SHADESIM_BUILD_PARAMETERS; }

InjectedFaults built_faults() {
  InjectedFaults f;
  for (const auto& p : built_parameters()) {
    if (p.name == "FAULT_LSB_ROW") f.lsb_row = static_cast<int>(p.value);
    if (p.name == "FAULT_STALL_ROW") f.stall_row = static_cast<int>(p.value);
    if (p.name == "FAULT_HANG_ROW") f.hang_row = static_cast<int>(p.value);
  }
  return f;
}

std::string parameter_text(const std::vector<VerilogParameter>& params) {
  std::string s;
  for (const auto& p : params) s += (s.empty() ? "" : " ") + p.name + "=" + std::to_string(p.value);
  return s;
}

CosimResult run_build(const CosimJob& job, const WaveWindow* waves) {
#ifdef SHADESIM_COSIM_SYSTEMC
  if (waves) throw InputError("waveforms need the trace-enabled C++ build (shadesim cosim --waves)");
  return run_verilated_systemc<Vshade_unit>(job);
#else
  return run_verilated_cpp<Vshade_unit>(job, waves);
#endif
}

struct Options {
  std::string config = "custom";  // the build's name, for reports
  std::string unit_path;
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
  uint64_t watchdog = 0;  // cycles without pix_valid_o that count as a hang; 0: from the cycle model
  std::string coverage_path;  // covered builds: FILE.dat (several jobs: FILE_<i>.dat)
  bool list = false;
};

nlohmann::json faults_json(const InjectedFaults& f) {
  nlohmann::json j = nlohmann::json::object();
  if (f.lsb_row >= 0) j["lsb_row"] = f.lsb_row;
  if (f.stall_row >= 0) j["stall_row"] = f.stall_row;
  if (f.hang_row >= 0) j["hang_row"] = f.hang_row;
  return j;
}

// One line naming everything needed to find the mismatch.
std::string mismatch_message(const Mismatch& m, const RtlConfig& c) {
  std::ostringstream os;
  if (m.kind == Mismatch::Kind::kHang) {
    os << "hang in configuration " << c.name << " [" << c.unit.to_string() << fault_text(c.faults)
       << "]: " << m.got << ", at cycle " << m.cycle << ", while expecting " << m.expected << " (scanline "
       << m.scanline << ")";
    return os.str();
  }
  os << to_string(m.kind) << " mismatch in configuration " << c.name << " [" << c.unit.to_string()
     << fault_text(c.faults) << "]: scanline " << m.scanline << " (y=" << m.y << "), x=" << m.x << ", cycle "
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

// Each job's coverage file: FILE itself for one job, FILE_<i>.dat for several (verilator_coverage
// merges them).
void set_coverage_paths(std::vector<CosimJob>& jobs, const std::string& path) {
  if (path.empty()) return;
  if (!kCovered) throw InputError("--coverage needs a covered build (shadesim regress --coverage picks it)");
  const std::filesystem::path p(path);
  for (size_t i = 0; i < jobs.size(); ++i) {
    jobs[i].coverage_path = jobs.size() == 1 ? path
                                             : (p.parent_path() / (p.stem().string() + "_" + std::to_string(i) +
                                                                   p.extension().string())).string();
  }
}

std::vector<CosimJob> make_jobs(const Options& o, const RtlConfig& build) {
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
    job.config = build;
    job.scenario = "replay";
    try {
      job.stream = CommandStream::load(o.stream_path);
      job.stream.validate(o.stream_path);
    } catch (const std::exception& e) {
      throw InputError(e.what());
    }
    if (config_to_json(job.stream.config) != config_to_json(build.unit)) {
      throw InputError(o.stream_path + ": stream configuration " + job.stream.config.to_string() +
                       " differs from --config " + build.name + " (" + build.unit.to_string() + ")");
    }
    job.stim = apply_overrides(Stimulus{}, o.seed);
    job.watchdog_cycles = o.watchdog;
    jobs.push_back(job);
    set_coverage_paths(jobs, o.coverage_path);
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
      job.config = build;
      job.scenario = name;
      const uint64_t seed = o.seed + static_cast<uint64_t>(k);
      job.stream = random_stream(build.unit, sc.shape, seed);
      job.stim = apply_overrides(sc.stim, seed);
      job.watchdog_cycles = o.watchdog;
      jobs.push_back(job);
    }
  }
  set_coverage_paths(jobs, o.coverage_path);
  return jobs;
}

// The unit this run simulates: --unit, else the replayed stream's header. It must map to the
// parameters this executable was Verilated with, or its pixels would be compared against a
// model of another unit.
RtlConfig resolve_build(const Options& o) {
  RtlConfig b;
  b.name = o.config;
  b.faults = built_faults();
  try {
    if (!o.unit_path.empty()) {
      std::ifstream is(o.unit_path);
      if (!is) throw InputError("--unit " + o.unit_path + ": cannot open");
      try {
        b.unit = load_unit_config(o.unit_path);
      } catch (const UnitConfigFileError& e) {
        throw InputError(std::string("--unit ") + e.what());
      }
    } else if (!o.stream_path.empty()) {
      b.unit = CommandStream::load(o.stream_path).config;
    } else {
      throw InputError("--unit FILE.json is required (or --stream, whose header names the unit)");
    }
  } catch (const CommandStreamError& e) {
    throw InputError(e.what());
  }
  const std::string want = parameter_text(built_parameters());
  const std::string got = parameter_text(shade_unit_parameters(b.unit, b.faults));
  if (want != got) {
    throw InputError("the unit " + b.unit.to_string() + " maps to shade_unit parameters {" + got +
                     "}, but this executable was Verilated with {" + want +
                     "}: run it through `shadesim cosim`, which builds the right one");
  }
  return b;
}

int run_all(const Options& o) {
  const RtlConfig build = resolve_build(o);
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
    if (expect_kind != "pixel" && expect_kind != "cycle" && expect_kind != "hang") {
      throw InputError("--expect-mismatch kind '" + expect_kind + "': expected pixel, cycle or hang");
    }
  }
  if (!o.waves_path.empty() && !kTraced) {
    throw InputError("--waves needs the trace-enabled build, which `shadesim cosim --waves FILE` picks");
  }

  const std::vector<CosimJob> jobs = make_jobs(o, build);
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
    out.result = run_build(job, nullptr);
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
      // shadesim cosim resolves --config (a named build or a UnitConfig file) again; a stream
      // alone names its unit in its header.
      const bool named = job.config.name != "custom" && job.config.name != "stream";
      out.replay = std::string(SHADESIM_EXE) + (named ? " --config " + job.config.name : "") + " --stream " + out.saved_stream +
                   ' ' + job.stim.to_args() + (o.watchdog > 0 ? " --watchdog " + std::to_string(o.watchdog) : "");
      if (m.kind == Mismatch::Kind::kHang) std::cout << "  HANG: " << mismatch_message(m, job.config) << '\n';
      std::cout << "  first mismatch (" << to_string(m.kind) << "): configuration " << job.config.name
                << " [" << job.config.unit.to_string() << fault_text(job.config.faults) << "]\n"
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
        const CosimResult again = run_build(job, &w);
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
  const std::vector<VerilogParameter> params = built_parameters();
  if (!json) {
    std::cout << SHADESIM_BACKEND << " build: " << parameter_text(params) << '\n';
    return;
  }
  nlohmann::json p = nlohmann::json::object();
  for (const auto& v : params) p[v.name] = v.value;
  std::cout << nlohmann::json{{"backend", SHADESIM_BACKEND}, {"traced", kTraced}, {"covered", kCovered}, {"parameters", p},
                              {"faults", faults_json(built_faults())}}
                   .dump(2)
            << '\n';
}

int cosim_main(int argc, char** argv) {
  CLI::App app{"Co-simulate the Verilated shade_unit (" SHADESIM_BACKEND
               " backend) against the bit-accurate model and the cycle model"};
  Options o;
  bool list_json = false;
  app.add_option("--unit", o.unit_path, "the unit (UnitConfig JSON) this build simulates");
  app.add_option("--config", o.config, "the build's name, for reports")->capture_default_str();
  app.add_flag("--list", o.list, "print the parameters this executable was Verilated with (--json: as JSON)");
  app.add_option("--scenario", o.scenario, "mixed, long, short, slow, maxbp, switch, tiny, edge, or all");
  app.add_option("--stream", o.stream_path, "replay a saved command stream (text form)");
  app.add_option("--seed", o.seed, "seed of the stream and of the stimulus (printed on every run)");
  app.add_option("--rows", o.rows, "override: scanlines per generated stream (for benchmarks)")->check(CLI::Range(1, 32768));
  app.add_option("--runs", o.runs, "consecutive seeds per scenario")->check(CLI::PositiveNumber);
  app.add_option("--gap-pct", o.gap_pct, "override: chance of idle cycles before a command word")->check(CLI::Range(0, 100));
  app.add_option("--max-gap", o.max_gap, "override: longest idle gap")->check(CLI::Range(1, 100000));
  app.add_option("--stall-pct", o.stall_pct, "override: chance of pix_ready low per cycle")->check(CLI::Range(0, 99));
  app.add_option("--expect-mismatch", o.expect,
                 "KIND:Y - succeed only if the first mismatch is KIND (pixel|cycle|hang) at scanline y=Y");
  app.add_option("--save-dir", o.save_dir, "where a failing run's command stream is saved");
  auto* json_opt = app.add_option("--json", o.json_path, "write each run's result as JSON to this file")
                       ->expected(0, 1);
  app.add_option("--waves", o.waves_path,
                 "on a mismatch, re-run with tracing and write an FST of the cycles around it (traced build)");
  app.add_option("--min-spec-pct", o.min_spec_pct,
                 "fail a run where the specular term changes fewer than this percentage of the pixels")
      ->check(CLI::Range(0.0, 100.0));
  app.add_option("--watchdog", o.watchdog,
                 "cycles without pix_valid_o, while pixels are still expected, that count as a hang "
                 "(default 0: the cycle model's longest pixel-less stretch on this stream + 1000)");
  app.add_option("--coverage", o.coverage_path,
                 "write the run's line/toggle/user coverage to FILE.dat, pass or fail (covered build)");
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
