// The co-simulation executable of one RTL build: the Verilated shade_unit (C++, SystemC, or C++
// with FST tracing) against the bit-accurate model (every pixel) and the cycle model (every
// pixel's exit cycle and cmd_ready_o on every cycle); sim/harness/cosim.h states the contract.
// shadesim builds one per parameter set into its cache (sim/eda/rtl_build.h) and runs it through
// `shadesim cosim`, which passes the unit as a file. This file is the executable's shared
// driver, compiled once into libshadesim_harness; each build adds its Verilated model through
// sim/harness/cosim_glue.cpp (sim/harness/cosim_executable.h):
//
//   <exe> --unit unit.json --config grey_s428w --scenario all --seed 1 --runs 3
//   <exe> --stream failing.cmds --seed 5 --gap-pct 30 ...   (replay: the stream names its unit)
//   <exe> --unit unit.json --stream s.cmds --json result.json
//   <exe> --unit unit.json --config fault_lsb --scenario mixed --waves fail.fst   (traced build)
//   <exe> --list [--json]
//
// The unit must map (model/rtl_parameters.h) to exactly the parameters this executable was
// Verilated with; whether it can inject the deliberate faults is compiled in beside them.
//
// Exit status: 0 every run passed (or the expected mismatch was found), 1 a mismatch, 2 bad
// input (unit of another build, unreadable or incompatible stream, bad option).
//
// --json FILE: one object per run (an array when there is more than one run):
//   {config, backend, traced, scenario, seed, stimulus: {gap_pct, max_gap, stall_pct}, passed,
//    cycles, pixels, scanlines, seconds, cycles_per_second,
//    first_mismatch: null | {kind, scanline, y, x, expected, got, cycle, message},
//      kind: pixel | cycle | ready | extra-pixel | hang | timeout (sim/harness/cosim.h says each),
//      before: null | an earlier ready mismatch this one follows from,
//    saved_stream: null | path, replay: null | command line, waves: null | {path, first_cycle,
//    last_cycle}}
// On bad input (exit 2) the file holds {"passed": false, "error": message} when it can be written.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <variant>

#include "model/rtl_parameters.h"
#include "model/unit_config_file.h"
#include "sim/cli/number_checks.h"
#include "sim/harness/cosim.h"
#include "sim/harness/cosim_executable.h"
#include "sim/harness/random_stream.h"
#include "sim/harness/verilated_dut.h"

namespace shadesim {
namespace {

// Bad input: exit status 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Whether this executable can inject the deliberate faults.
InjectedFaults built_faults(const CosimExecutable& exe) {
  InjectedFaults f;
  f.hooks = exe.fault_hooks;
  return f;
}

std::string parameter_text(const std::vector<VerilogParameter>& params) {
  std::string s;
  for (const auto& p : params) s += (s.empty() ? "" : " ") + p.name + "=" + p.literal();
  return s;
}

// The kinds --expect-mismatch accepts (a deliberate fault may show as any of them).
constexpr Mismatch::Kind kExpectableKinds[] = {Mismatch::Kind::kPixel, Mismatch::Kind::kCycle,
                                               Mismatch::Kind::kReady, Mismatch::Kind::kExtraPixel,
                                               Mismatch::Kind::kHang,  Mismatch::Kind::kTimeout};

struct Options {
  std::string config = "custom";  // the build's name, for reports
  std::string unit_path;
  std::string scenario = "mixed";
  std::string stream_path;
  uint64_t seed = 1;
  int runs = 1;
  int rows = 0;  // 0: the scenario's own
  int gap_pct = -1, max_gap = -1, stall_pct = -1;
  std::string expect;  // KIND:Y[:X]
  std::string fault;   // SITE@Y (sim/harness/fault_site.h)
  std::string save_dir = ".";
  std::string json_path;
  std::string waves_path;
  std::string replay_prefix;  // how replay lines start; empty: the executable's own command
  uint64_t waves_before = 200, waves_after = 16;
  double min_spec_pct = 0;
  uint64_t watchdog =
      0;  // cycles without pix_valid_o that count as a hang; 0: from the cycle model
  std::string coverage_path;  // covered builds: FILE.dat (several jobs: FILE_<i>.dat)
  bool list = false;
};

// The build's unit and, on a fault run, the fault it injects.
std::string unit_text(const CosimJob& job) {
  return job.config.unit.to_string() + fault_text(job.config.faults) +
         (job.fault.any() ? " fault=" + job.fault.text() : "");
}

// One line naming everything needed to find the mismatch.
std::string mismatch_message(const Mismatch& m, const CosimJob& job) {
  const RtlConfig& c = job.config;
  std::ostringstream os;
  if (m.kind == Mismatch::Kind::kHang) {
    os << "hang in configuration " << c.name << " [" << unit_text(job) << "]: " << m.got
       << ", at cycle " << m.cycle << ", while expecting " << m.expected << " (scanline "
       << m.scanline << ")";
    return os.str();
  }
  os << to_string(m.kind) << " mismatch in configuration " << c.name << " [" << unit_text(job)
     << "]: scanline " << m.scanline << " (y=" << m.y << "), x=" << m.x << ", cycle " << m.cycle
     << ": expected " << m.expected << ", got " << m.got;
  if (!m.before.empty()) os << " (" << m.before << ")";
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

nlohmann::json outcome_json(const Outcome& o, const CosimExecutable& exe) {
  const CosimResult& r = o.result;
  const Stimulus& s = o.job.stim;
  nlohmann::json j;
  j["config"] = o.job.config.name;
  j["backend"] = exe.backend;
  j["traced"] = exe.traced;
  j["scenario"] = o.job.scenario;
  j["seed"] = s.seed;
  j["stimulus"] = {{"gap_pct", s.gap_pct}, {"max_gap", s.max_gap}, {"stall_pct", s.stall_pct}};
  j["passed"] = r.passed();
  j["cycles"] = r.cycles;
  j["pixels"] = r.pixels;
  j["scanlines"] = r.scanlines;
  j["seconds"] = r.seconds;
  j["cycles_per_second"] = r.seconds > 0 ? static_cast<double>(r.cycles) / r.seconds : 0.0;
  j["spec_affected_pixels"] =
      o.spec_affected >= 0 ? nlohmann::json(o.spec_affected) : nlohmann::json(nullptr);
  if (r.passed()) {
    j["first_mismatch"] = nullptr;
  } else {
    const Mismatch& m = r.first;
    j["first_mismatch"] = {
        {"kind", to_string(m.kind)},
        {"scanline", m.scanline},
        {"y", m.y},
        {"x", m.x},
        {"expected", m.expected},
        {"got", m.got},
        {"cycle", m.cycle},
        {"before", m.before.empty() ? nlohmann::json(nullptr) : nlohmann::json(m.before)},
        {"message", mismatch_message(m, o.job)}};
  }
  j["saved_stream"] =
      o.saved_stream.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.saved_stream);
  j["replay"] = o.replay.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.replay);
  if (o.waves.path.empty()) {
    j["waves"] = nullptr;
  } else {
    j["waves"] = {
        {"path", o.waves.path}, {"first_cycle", o.waves.first}, {"last_cycle", o.waves.last}};
  }
  return j;
}

// Each job's coverage file: FILE itself for one job, FILE_<i>.dat for several (verilator_coverage
// merges them).
void set_coverage_paths(std::vector<CosimJob>& jobs, const std::string& path) {
  if (path.empty()) return;
  const std::filesystem::path p(path);
  for (size_t i = 0; i < jobs.size(); ++i) {
    jobs[i].coverage_path =
        jobs.size() == 1 ? path
                         : (p.parent_path() /
                            (p.stem().string() + "_" + std::to_string(i) + p.extension().string()))
                               .string();
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
                       " differs from --config " + build.name + " (" + build.unit.to_string() +
                       ")");
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
RtlConfig resolve_build(const Options& o, const CosimExecutable& exe) {
  RtlConfig b;
  b.name = o.config;
  b.faults = built_faults(exe);
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
  const std::string want = parameter_text(exe.parameters);
  const std::string got = parameter_text(shade_unit_parameters(b.unit));
  if (want != got) {
    throw InputError("the unit " + b.unit.to_string() + " maps to shade_unit parameters {" + got +
                     "}, but this executable was Verilated with {" + want +
                     "}: run it through `shadesim cosim`, which builds the right one");
  }
  return b;
}

// --expect-mismatch KIND:Y[:X]: the run succeeds only if its first mismatch is KIND on row Y,
// and at column X when given. X "first" is the row's first pixel as the stream orders them: the
// x0 of the stream's first SPAN on row Y, so a fault on every pixel of a row is checked to show
// on the first one, without asking the model under test where that is.
struct Expectation {
  std::string kind;  // empty: none expected
  int y = -1;
  std::optional<int> x;  // none: any column
  bool first_of_row = false;
  std::string text;  // as given

  bool active() const { return !kind.empty(); }
  bool met_by(const Mismatch& m, const CommandStream& stream) const {
    if (to_string(m.kind) != kind || m.y != y) return false;
    if (first_of_row) return m.x == first_span_x(stream, y);
    return !x || m.x == *x;
  }

  static int first_span_x(const CommandStream& stream, int row) {
    for (const Command& c : stream.commands) {
      if (const auto* span = std::get_if<SpanCmd>(&c); span != nullptr && span->y == row) {
        return span->x0;
      }
    }
    return -1;  // the stream has no span on the row: no mismatch can be its first pixel
  }
};

Expectation parse_expectation(const std::string& text) {
  Expectation e;
  if (text.empty()) return e;
  e.text = text;
  const auto colon = text.find(':');
  const auto second = colon == std::string::npos ? colon : text.find(':', colon + 1);
  try {
    if (colon == std::string::npos) throw std::invalid_argument(text);
    e.kind = text.substr(0, colon);
    const std::string row = text.substr(colon + 1, second - colon - 1);
    size_t used = 0;
    e.y = std::stoi(row, &used);
    if (used != row.size()) throw std::invalid_argument(text);
    if (second != std::string::npos) {
      const std::string column = text.substr(second + 1);
      if (column == "first") {
        e.first_of_row = true;
      } else {
        e.x = std::stoi(column, &used);
        if (used != column.size()) throw std::invalid_argument(text);
      }
    }
  } catch (const std::logic_error&) {
    throw InputError("--expect-mismatch '" + text +
                     "': expected KIND:Y or KIND:Y:X (X a column or 'first'), e.g. pixel:17 or "
                     "pixel:17:first");
  }
  std::string kinds;
  for (Mismatch::Kind k : kExpectableKinds) {
    if (to_string(k) == e.kind) return e;
    kinds += (kinds.empty() ? "" : ", ") + to_string(k);
  }
  throw InputError("--expect-mismatch kind '" + e.kind + "': expected one of " + kinds);
}

// --fault SITE@Y: only a build with fault hooks injects it, and only where the unit can show it.
FaultInjection parse_fault_option(const std::string& text, const RtlConfig& build) {
  if (text.empty()) return {};
  FaultInjection f;
  try {
    f = parse_fault(text);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("--fault: ") + e.what());
  }
  if (!build.faults.hooks) {
    throw InputError("--fault " + text +
                     ": this build has no fault hooks (a named build with "
                     "\"fault_hooks\": true in sim/harness/builds.json has them, e.g. grey_s428w)");
  }
  if (const std::string why = fault_unsupported(f, build.unit); !why.empty()) {
    throw InputError("--fault " + text + ": " + why);
  }
  return f;
}

// Options that only make sense for some runs, checked before anything runs.
void check_run_options(const Options& o, const std::vector<CosimJob>& jobs,
                       const CosimExecutable& exe) {
  if (!o.coverage_path.empty() && !exe.covered) {
    throw InputError("--coverage needs a covered build (shadesim regress --coverage picks it)");
  }
  if (!o.waves_path.empty() && !exe.traced) {
    throw InputError(
        "--waves needs the trace-enabled build, which `shadesim cosim --waves FILE` picks");
  }
  if (exe.one_job_per_process && jobs.size() != 1) {
    throw InputError(
        "the SystemC kernel elaborates once per process, so this backend runs one job; got " +
        std::to_string(jobs.size()) + " (use one --scenario and --runs 1)");
  }
  if (!o.waves_path.empty() && jobs.size() != 1) {
    throw InputError(
        "--waves writes one file: run one job (one --scenario or --stream, --runs 1); got " +
        std::to_string(jobs.size()));
  }
}

// The one-line summary of a run.
void print_run_line(const CosimJob& job, const CosimResult& r, const CosimExecutable& exe) {
  char line[512];
  std::snprintf(
      line, sizeof line,
      "%-8s %-12s %-7s seed=%-6llu pixels=%-7llu scanlines=%-5llu cycles=%-8llu "
      "cyc/px=%.3f wall=%.3fs %.2f Mcycles/s  %s",
      exe.backend.c_str(), job.config.name.c_str(), job.scenario.c_str(),
      static_cast<unsigned long long>(job.stim.seed), static_cast<unsigned long long>(r.pixels),
      static_cast<unsigned long long>(r.scanlines), static_cast<unsigned long long>(r.cycles),
      r.pixels ? static_cast<double>(r.cycles) / static_cast<double>(r.pixels) : 0.0, r.seconds,
      r.seconds > 0 ? static_cast<double>(r.cycles) / r.seconds / 1e6 : 0.0,
      r.passed() ? (r.pixels > 0 ? "PASS" : "EMPTY") : "MISMATCH");
  std::cout << line << '\n';
}

// How many of the model's pixels the specular term changes: the same stream with every
// spec_colour set to 0, pixel by pixel. A run checks the specular units' bits only where this
// is non-zero.
uint64_t specular_affected_pixels(const CosimJob& job, const std::vector<PixelOut>& expected) {
  CommandStream dark = job.stream;
  for (auto& cmd : dark.commands) {
    if (auto* m = std::get_if<MaterialCmd>(&cmd))
      std::fill(m->spec_colour.begin(), m->spec_colour.end(), 0);
  }
  const std::vector<PixelOut> plain = ShadeUnit(job.config.unit).run(dark);
  uint64_t n = 0;
  for (size_t i = 0; i < expected.size() && i < plain.size(); ++i) {
    for (int c = 0; c < job.config.unit.channels; ++c) {
      if (expected[i].colour[c] != plain[i].colour[c]) {
        ++n;
        break;
      }
    }
  }
  return n;
}

// With real specular hardware: how much of the run exercised it (Outcome::spec_affected).
// False when that is under --min-spec-pct.
bool check_specular_share(Outcome& out, const Options& o) {
  if (out.job.config.unit.specular.kind == SpecularUnitKind::kIdeal ||
      out.job.config.unit.specular.kind == SpecularUnitKind::kNone)
    return true;  // no specular hardware to exercise
  const std::vector<PixelOut> expected = ShadeUnit(out.job.config.unit).run(out.job.stream);
  out.spec_affected = static_cast<int64_t>(specular_affected_pixels(out.job, expected));
  const double pct = expected.empty() ? 0.0
                                      : 100.0 * static_cast<double>(out.spec_affected) /
                                            static_cast<double>(expected.size());
  std::printf("  specular term changes %lld of %zu pixels (%.1f%%)\n",
              static_cast<long long>(out.spec_affected), expected.size(), pct);
  if (pct >= o.min_spec_pct) return true;
  std::printf("  FAIL: fewer than --min-spec-pct %.1f%% of the pixels exercise the specular unit\n",
              o.min_spec_pct);
  return false;
}

// The command that reproduces a failed run. Fault hooks exist only in named builds
// (sim/harness/builds.json), so a build with them is named by --config, and a fault run's fault
// by --fault; any other unit is named by the saved stream's header, which `shadesim cosim
// --stream` reads (a name such as own:sphere, regress's scene-own configuration, is no argument
// `cosim --config` accepts).
std::string replay_line(const CosimJob& job, const std::string& stream_path, const Options& o,
                        const CosimExecutable& exe) {
  const bool hooks = job.config.faults.hooks;
  return (o.replay_prefix.empty() ? exe.command : o.replay_prefix) +
         (hooks ? " --config " + job.config.name : "") +
         (job.fault.any() ? " --fault " + job.fault.text() : "") + " --stream " + stream_path +
         ' ' + job.stim.to_args() +
         (o.watchdog > 0 ? " --watchdog " + std::to_string(o.watchdog) : "");
}

// A failed run: its stream saved into --save-dir, the replay command (Outcome::saved_stream,
// replay).
void save_failure(Outcome& out, const Options& o, const CosimExecutable& exe) {
  const CosimJob& job = out.job;
  std::filesystem::create_directories(o.save_dir);
  // The configuration name may be a path (--config FILE.json) or carry a ':' (own:sphere).
  std::string stem = job.config.name + "_" + job.scenario + "_" + std::to_string(job.stim.seed);
  for (char& c : stem) {
    if (c == '/' || c == ':' || c == '\\') c = '_';
  }
  out.saved_stream = o.save_dir + "/" + stem + ".cmds";
  job.stream.save(out.saved_stream);
  out.replay = replay_line(job, out.saved_stream, o, exe);
}

void print_mismatch(const Outcome& out) {
  const Mismatch& m = out.result.first;
  const RtlConfig& c = out.job.config;
  if (m.kind == Mismatch::Kind::kHang)
    std::cout << "  HANG: " << mismatch_message(m, out.job) << '\n';
  std::cout << "  first mismatch (" << to_string(m.kind) << "): configuration " << c.name << " ["
            << unit_text(out.job) << "]\n"
            << "    scanline " << m.scanline << " (y=" << m.y << "), x=" << m.x << ", cycle "
            << m.cycle << '\n'
            << "    expected " << m.expected << '\n'
            << "    got      " << m.got << '\n'
            << (m.before.empty() ? "" : "    before it: " + m.before + "\n")
            << "    stream saved to " << out.saved_stream << '\n'
            << "    replay: " << out.replay << '\n';
}

// The same job again (deterministic), dumping only the window of cycles around its first
// mismatch into --waves (Outcome::waves).
void write_waveform(Outcome& out, const Options& o, const CosimExecutable& exe) {
  const Mismatch& m = out.result.first;
  WaveWindow w;
  w.path = o.waves_path;
  w.first = m.cycle > o.waves_before ? m.cycle - o.waves_before : 0;
  w.last = m.cycle + o.waves_after;
  const std::filesystem::path parent = std::filesystem::path(w.path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  const CosimResult again = exe.run(out.job, &w);
  if (again.first.kind != m.kind || again.first.cycle != m.cycle) {
    std::cout << "    WARNING: the traced re-run mismatched differently ("
              << to_string(again.first.kind) << " at cycle " << again.first.cycle << ")\n";
  }
  out.waves = w;
  std::cout << "    waves: " << w.path << " (cycles " << w.first << ".." << w.last
            << ", time = " << kWaveUnitsPerCycle << " x (cycle + " << kResetCycles << "))\n";
}

void write_results_json(const std::string& path, const std::vector<Outcome>& outcomes,
                        const CosimExecutable& exe) {
  if (path.empty()) return;
  nlohmann::json j;
  if (outcomes.size() == 1) {
    j = outcome_json(outcomes.front(), exe);
  } else {
    j = nlohmann::json::array();
    for (const auto& out : outcomes) j.push_back(outcome_json(out, exe));
  }
  write_json(path, j);
}

// Runs the jobs in order; with --expect-mismatch, stops at the first failed run and says
// whether it failed as expected.
int run_all(const Options& o, const CosimExecutable& exe) {
  const RtlConfig build = resolve_build(o, exe);
  const Expectation expect = parse_expectation(o.expect);
  const FaultInjection fault = parse_fault_option(o.fault, build);
  std::vector<CosimJob> jobs = make_jobs(o, build);
  for (CosimJob& job : jobs) job.fault = fault;
  // A fault on a row no run's stream covers can never show: refuse it rather than pass silently.
  if (fault.any() && std::none_of(jobs.begin(), jobs.end(), [&](const CosimJob& job) {
        return Expectation::first_span_x(job.stream, fault.row) >= 0;
      })) {
    throw InputError(
        "--fault " + o.fault + ": row " + std::to_string(fault.row) + " has no pixels in " +
        (jobs.size() == 1 ? "the " + jobs[0].scenario + " stream (seed " +
                                std::to_string(jobs[0].stim.seed) + ")"
                          : "any of the " + std::to_string(jobs.size()) + " runs' streams") +
        ", so the fault could never show; choose a row with spans");
  }
  check_run_options(o, jobs, exe);

  std::vector<Outcome> outcomes;
  int failures = 0;
  for (const auto& job : jobs) {
    Outcome out;
    out.job = job;
    out.result = exe.run(job, nullptr);
    print_run_line(job, out.result, exe);
    if (!check_specular_share(out, o)) ++failures;
    if (out.result.passed()) {
      // No pixel compared is no evidence: a run that shaded nothing is not a pass (issue 23).
      if (out.result.pixels == 0) {
        std::cout << "  FAIL: the run shaded 0 pixels in " << out.result.cycles
                  << " cycles: nothing was compared (an empty stream?)\n";
        ++failures;
      }
      outcomes.push_back(out);
      continue;
    }
    ++failures;
    save_failure(out, o, exe);
    print_mismatch(out);
    if (!o.waves_path.empty()) write_waveform(out, o, exe);
    outcomes.push_back(out);
    if (expect.active()) {
      const bool as_expected = expect.met_by(out.result.first, job.stream);
      std::cout << (as_expected
                        ? "  the deliberate fault was caught where expected\n"
                        : "  FAIL: expected the first mismatch to be " + expect.text +
                              (expect.first_of_row ? " (x=" +
                                                         std::to_string(Expectation::first_span_x(
                                                             job.stream, expect.y)) +
                                                         ")"
                                                   : "") +
                              "\n");
      write_results_json(o.json_path, outcomes, exe);
      return as_expected ? 0 : 1;
    }
  }
  write_results_json(o.json_path, outcomes, exe);
  if (expect.active()) {
    std::cout << "FAIL: expected a mismatch (" << expect.text << "), but every run passed\n";
    return 1;
  }
  return failures == 0 ? 0 : 1;
}

void print_list(bool json, const CosimExecutable& exe) {
  const std::vector<VerilogParameter>& params = exe.parameters;
  if (!json) {
    std::cout << exe.backend << " build: " << parameter_text(params) << '\n';
    return;
  }
  nlohmann::json p = nlohmann::json::object();
  for (const auto& v : params) {
    if (v.slots.empty())
      p[v.name] = v.value;
    else
      p[v.name] = v.slots;
  }
  std::cout << nlohmann::json{{"backend", exe.backend},
                              {"traced", exe.traced},
                              {"covered", exe.covered},
                              {"parameters", p},
                              {"fault_hooks", built_faults(exe).hooks}}
                   .dump(2)
            << '\n';
}

}  // namespace

int cosim_main(int argc, char** argv, const CosimExecutable& exe) {
  CLI::App app{"Co-simulate the Verilated shade_unit (" + exe.backend +
               " backend) against the bit-accurate model and the cycle model"};
  Options o;
  bool list_json = false;
  app.add_option("--unit", o.unit_path, "the unit (UnitConfig JSON) this build simulates");
  app.add_option("--config", o.config, "the build's name, for reports")->capture_default_str();
  app.add_flag("--list", o.list,
               "print the parameters this executable was Verilated with (--json: as JSON)");
  app.add_option("--scenario", o.scenario,
                 "mixed, long, short, slow, maxbp, switch, tiny, edge, or all");
  app.add_option("--stream", o.stream_path, "replay a saved command stream (text form)");
  app.add_option("--seed", o.seed, "seed of the stream and of the stimulus (printed on every run)");
  app.add_option("--rows", o.rows, "override: scanlines per generated stream (for benchmarks)")
      ->check(CLI::Range(1, 32768));
  app.add_option("--runs", o.runs, "consecutive seeds per scenario")->check(positive_number());
  app.add_option("--gap-pct", o.gap_pct, "override: chance of idle cycles before a command word")
      ->check(CLI::Range(0, 100));
  app.add_option("--max-gap", o.max_gap, "override: longest idle gap")
      ->check(CLI::Range(1, 100000));
  app.add_option("--stall-pct", o.stall_pct, "override: chance of pix_ready low per cycle")
      ->check(CLI::Range(0, 99));
  app.add_option("--expect-mismatch", o.expect,
                 "KIND:Y[:X] - succeed only if the first mismatch is KIND "
                 "(pixel|cycle|ready|extra-pixel|hang|timeout) "
                 "at scanline y=Y (and column X; 'first': the x0 of the stream's first span "
                 "on row Y)");
  std::string sites;
  for (const FaultSiteInfo& s : fault_sites())
    sites += std::string("\n    ") + s.name + ": " + s.what;
  app.add_option("--fault", o.fault,
                 "SITE@Y - inject one deliberate fault on row Y (a build with fault hooks, e.g. "
                 "grey_s428w); SITE is one of:" +
                     sites);
  app.add_option("--replay-prefix", o.replay_prefix,
                 "the shadesim command line replay lines start with (shadesim cosim and regress "
                 "pass it: backend, cache, netlist)");
  app.add_option("--save-dir", o.save_dir, "where a failing run's command stream is saved");
  auto* json_opt =
      app.add_option("--json", o.json_path, "write each run's result as JSON to this file")
          ->expected(0, 1);
  app.add_option(
      "--waves", o.waves_path,
      "on a mismatch, re-run with tracing and write an FST of the cycles around it (traced build)");
  app.add_option(
         "--min-spec-pct", o.min_spec_pct,
         "fail a run where the specular term changes fewer than this percentage of the pixels")
      ->check(CLI::Range(0.0, 100.0));
  app.add_option(
      "--watchdog", o.watchdog,
      "cycles without pix_valid_o, while pixels are still expected, that count as a hang "
      "(default 0: the cycle model's longest pixel-less stretch on this stream + 1000)");
  app.add_option(
      "--coverage", o.coverage_path,
      "write the run's line/toggle/user coverage to FILE.dat, pass or fail (covered build)");
  app.add_option("--waves-before", o.waves_before, "cycles before the mismatch in the waveform")
      ->capture_default_str();
  app.add_option("--waves-after", o.waves_after, "cycles after the mismatch in the waveform")
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  list_json = json_opt->count() > 0;
  if (o.list) {
    if (list_json && !o.json_path.empty()) {
      std::cerr << exe.command
                << ": error: --list --json prints to stdout; it takes no file name\n";
      return 2;
    }
    print_list(list_json, exe);
    return 0;
  }
  if (list_json && o.json_path.empty()) {
    std::cerr << exe.command
              << ": error: --json needs a file name (only --list --json prints to stdout)\n";
    return 2;
  }
  try {
    return run_all(o, exe);
  } catch (const std::exception& e) {  // InputError, or a file the run could not write
    std::cerr << exe.command << ": error: " << e.what() << '\n';
    if (!o.json_path.empty()) {
      std::ofstream os(o.json_path);
      if (os) os << nlohmann::json{{"passed", false}, {"error", e.what()}}.dump(2) << '\n';
    }
    return 2;
  }
}

}  // namespace shadesim

namespace shadesim {

std::vector<VerilogParameter> built_parameters(const BuiltModel& model) {
  std::vector<VerilogParameter> out;
  for (int i = 0; i < model.parameter_count; ++i) {
    const BuiltParameter& p = model.parameters[i];
    if (p.slots) {
      out.emplace_back(p.name, std::vector<int64_t>(p.slots, p.slots + p.slot_count));
    } else {
      out.emplace_back(p.name, p.value);
    }
  }
  return out;
}

CosimExecutable executable_of(const BuiltModel& model, const std::string& backend,
                              const std::string& command) {
  CosimExecutable exe;
  exe.parameters = built_parameters(model);
  exe.covered = model.covered;
  exe.fault_hooks = model.fault_hooks;
  exe.traced = model.traced;
  exe.backend = backend;
  exe.command = command;
  return exe;
}

int cosim_main_or_error(int argc, char** argv, const CosimExecutable& exe) {
  try {
    return cosim_main(argc, argv, exe);
  } catch (const std::exception& e) {
    std::cerr << exe.command << ": error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace shadesim
