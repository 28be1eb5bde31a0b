// The co-simulation executable's engine (sim/harness/cosim_run.h): its options, already parsed
// (sim/harness/cosim_options.h), become jobs run on the Verilated model against the models, with
// a line per run, the failures' saved streams and replay lines, waveform re-runs and --json.
#include "sim/harness/cosim_run.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "model/rtl_parameters.h"
#include "model/unit_config_file.h"
#include "sim/harness/cosim.h"
#include "sim/harness/random_stream.h"

namespace shadesim::cosim_exe {
namespace {

// Whether this executable can inject the deliberate faults (compiled in beside its parameters).
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
  if (!o.trace_run_path.empty() && (!exe.traced || jobs.size() != 1)) {
    throw InputError(
        "--trace-run needs the trace-enabled build and one job (one --stream or "
        "--scenario, --runs 1)");
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

// --trace-run: the passed run again, every cycle it clocked dumped (Outcome::waves). A run stops
// on its last drain cycle (Lockstep::keep_going), so a window ending there leaves it unchanged.
void trace_whole_run(Outcome& out, const Options& o, const CosimExecutable& exe) {
  const CycleConfig timing = CycleConfig::of(out.job.config.unit);
  WaveWindow w;
  w.path = o.trace_run_path;
  w.first = 0;
  w.last = out.result.cycles - 1 + drain_cycles(CycleModel(timing), timing);
  const std::filesystem::path parent = std::filesystem::path(w.path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  const CosimResult again = exe.run(out.job, &w);
  if (!again.passed() || again.cycles != out.result.cycles) {
    throw std::runtime_error("--trace-run: the traced run differs from the run (" +
                             std::to_string(again.cycles) + " cycles against " +
                             std::to_string(out.result.cycles) + ")");
  }
  out.waves = w;
  std::cout << "  trace: " << w.path << " (cycles " << w.first << ".." << w.last << ")\n";
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
      // No pixel compared is no evidence: a run that shaded nothing is not a pass.
      if (out.result.pixels == 0) {
        std::cout << "  FAIL: the run shaded 0 pixels in " << out.result.cycles
                  << " cycles: nothing was compared (an empty stream?)\n";
        ++failures;
      } else if (!o.trace_run_path.empty()) {
        trace_whole_run(out, o, exe);
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

}  // namespace

int run(const Options& o, const CosimExecutable& exe) {
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

}  // namespace shadesim::cosim_exe
