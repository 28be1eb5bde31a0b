// shadesim regress's engine (its options: sim/cli/regress.cpp): the main job. Every scene x
// configuration x simulation backend: the host encodes the scene for the configuration's unit,
// shadesim builds the configuration's RTL on demand (sim/eda/verilator/rtl_build.h) and its
// co-simulation executable replays the stream against the bit-accurate model and the cycle model;
// this command collects, tabulates and reports.
//
// By default each scene runs on its own configuration (the smallest unit that shades it); the
// named builds (sim/harness/builds.json) with --configs, any other unit with --config FILE.json.
//
// Beyond one machine (README "Regression on many machines"): the job list is fixed before any
// run (scenes x configurations x backends, seeds numbered in that order), so --shard I/N and
// --emit-jobs FILE split it the same way on every host; each run writes its record into its own
// folder as soon as it ends (sim/regress/regress_results.h), --resume DIR runs only what is not
// there, and `shadesim merge` puts the folders back together.
#include "sim/regress/regress.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "derive/derive_config.h"
#include "host/frame.h"
#include "model/text_file.h"
#include "sim/eda/common/process.h"
#include "sim/eda/verilator/coverage.h"
#include "sim/eda/verilator/replay.h"
#include "sim/eda/verilator/rtl_build.h"
#include "sim/eda/yosys/unit_netlist.h"
#include "sim/engines/fixed_text.h"
#include "sim/engines/unit_choice.h"
#include "sim/harness/random_stream.h"
#include "sim/regress/interrupt.h"
#include "sim/regress/netlist_source.h"
#include "sim/regress/regress_coverage.h"
#include "sim/regress/regress_plan.h"
#include "sim/regress/regress_results.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

struct Job {
  RunSpec spec;
  RtlConfig build;
  std::string executable;  // the build's co-simulation executable
  std::string unit_path;   // the unit as JSON, for --unit
  RunRecord rec;
};

void save_record(const Job& j);

RtlBuildOptions build_options(const RegressOptions& o) {
  RtlBuildOptions b;
  b.cache_dir = o.cache;
  b.make_jobs = 1;  // builds run side by side
  b.coverage = o.coverage;
  return b;
}

// Replaces each pending job's netlist token by the netlist's path (an error for the job when
// Yosys failed), and says what each netlist is.
void resolve_netlists(std::vector<Job>& jobs, NetlistSource& netlists) {
  std::set<std::string> told;
  for (auto& j : jobs) {
    if (j.build.netlist.empty()) continue;
    const std::string token = j.build.netlist;
    j.build.netlist.clear();
    if (j.rec.status != "pending") continue;
    try {
      const UnitNetlist n = netlists.get(token);
      j.build.netlist = n.path;
      j.rec.unit_text += " [gate-level netlist, " + std::to_string(n.gate_equivalents) + " GE]";
      if (told.insert(n.path).second) {
        std::cout << "regress: netlist of " << j.build.name << ": " << n.path << " (" << n.cells
                  << " cells, " << n.flip_flops << " flip-flops, " << n.gate_equivalents << " GE"
                  << (n.ram_bits ? ", " + std::to_string(n.ram_bits) + " table RAM bits" : "")
                  << "; " << (n.from_cache ? "cached, Yosys took " : "Yosys ") << std::fixed
                  << std::setprecision(1) << n.seconds << " s" << std::defaultfloat << ")"
                  << std::endl;
      }
    } catch (const std::exception& e) {
      j.rec.status = "error";
      j.rec.message = std::string("netlist synthesis failed: ") + e.what();
      save_record(j);
    }
  }
}

// A path of a plan, from the folder the plan was made in.
std::string from_base(const fs::path& base, const std::string& path) {
  return base.empty() || fs::path(path).is_absolute() ? path : (base / path).string();
}

// `origin`: for an own unit, whether it was derived now or reused (own_unit).
RtlConfig resolve_config(const RunSpec& s, const fs::path& base, std::string* origin) {
  if (s.config_kind == kOwnUnit) return own_unit(from_base(base, s.scene), origin);
  if (s.config_kind == kDefaultUnit) return resolve_unit(kDefaultUnit, from_base(base, s.scene));
  if (s.config_kind == "named") return named_build(named_builds_path(), s.config);
  return resolve_rtl_config(from_base(base, s.config), "--config");
}

// Whether any material of the stream lights a specular term (a build with no specular hardware
// cannot match the model there).
bool has_highlights(const CommandStream& stream) {
  for (const auto& cmd : stream.commands) {
    if (const auto* m = std::get_if<MaterialCmd>(&cmd)) {
      for (auto v : m->spec_colour)
        if (v != 0) return true;
    }
  }
  return false;
}

void save_record(const Job& j) {
  write_file_atomically((fs::path(j.rec.dir) / "run.json").string(),
                        record_json(j.rec).dump(2) + '\n');
}

// The replay command for a run the harness gave none for (a timeout, a crash).
std::string replay_command(const Job& j, const RunSettings& settings, const RegressOptions& o) {
  std::string cmd = cosim_replay_prefix(j.spec.backend, o.cache, o.netlist, o.netlist_cache);
  if (j.spec.config_kind == "named" || j.spec.config_kind == "file")
    cmd += " --config " + j.spec.config;
  cmd += " --stream " + j.rec.stream + " --seed " + std::to_string(j.spec.seed) + " --gap-pct " +
         std::to_string(settings.gap_pct) + " --max-gap " + std::to_string(settings.max_gap) +
         " --stall-pct " + std::to_string(settings.stall_pct);
  if (settings.watchdog > 0) cmd += " --watchdog " + std::to_string(settings.watchdog);
  if (!settings.fault.empty()) cmd += " --fault " + settings.fault;
  return cmd;
}

// An upper estimate of the cycles a run of `pixels` pixels simulates: under the regression's gaps
// and back-pressure a pixel takes under 2 cycles on every shipped unit (1.28-1.49); 4 leaves room
// for slow specular units.
uint64_t expected_cycles(uint64_t pixels) { return 4 * pixels; }

// The optimisation of a build whose runs simulate `cycles` (--opt, else by their length).
RtlOptimization build_optimization(const RegressOptions& o, uint64_t cycles) {
  return o.optimization.empty() ? choose_optimization(cycles, o.coverage)
                                : parse_rtl_optimization(o.optimization);
}

// Host side: encode each scene for each configuration, into each of its runs' folders. One scene
// and configuration at a time (mesh import limits the process's address space while it runs, so
// it is not done on several threads at once). A run the scene does not fit is skipped, one the
// host cannot prepare is an error; either is recorded at once.
// `prefetch` starts each configuration's Verilation as soon as its first run is set up (its
// length says whether the build checks the SVA: checks_assertions), beside the host setup of
// the scenes that follow.
std::vector<Job> plan_jobs(const std::vector<RunSpec>& specs, const fs::path& out,
                           const fs::path& base, RtlPrefetch& prefetch, NetlistSource* netlists,
                           const RegressOptions& o, const RunSettings& settings) {
  std::vector<Job> jobs;
  std::map<std::string, size_t> first_of_pair;  // scene + config -> its first job
  for (const auto& spec : specs) {
    Job j;
    j.spec = spec;
    j.rec.spec = spec;
    j.rec.scene_name = scene_label(spec.scene);
    j.rec.dir = run_dir(out, spec).string();
    j.rec.stream = (fs::path(j.rec.dir) / "stream.cmds").string();
    j.unit_path = (fs::path(j.rec.dir) / "unit.json").string();
    fs::create_directories(j.rec.dir);
    const std::string pair = spec.scene + '\n' + spec.config + '\n' + std::to_string(spec.seed);
    const auto done = first_of_pair.find(pair);
    if (done != first_of_pair.end()) {
      // The pair's other backend: the same unit and stream.
      const Job& twin = jobs[done->second];
      j.build = twin.build;
      if (twin.rec.status == "pending" && !netlists) {
        prefetch.add(j.build, parse_cosim_backend(spec.backend),
                     build_optimization(o, expected_cycles(twin.rec.pixels)));
      }
      j.rec.unit = twin.rec.unit;
      j.rec.unit_text = twin.rec.unit_text;
      j.rec.pixels = twin.rec.pixels;
      j.rec.status = twin.rec.status;
      j.rec.message = twin.rec.message;
      if (j.rec.status == "pending") {
        fs::copy_file(twin.rec.stream, j.rec.stream, fs::copy_options::overwrite_existing);
        fs::copy_file(twin.unit_path, j.unit_path, fs::copy_options::overwrite_existing);
      }
    } else {
      first_of_pair[pair] = jobs.size();
      try {
        std::string origin;
        j.build = build_for_run(resolve_config(spec, base, &origin), !settings.fault.empty());
        j.build.name = spec.config;
        if (netlists) {
          // A token until resolve_netlists (the build's key needs the netlist's contents).
          j.build.netlist = netlists->start(j.build.unit);
        }
        j.rec.unit = nlohmann::json::parse(config_to_json(j.build.unit));
        j.rec.unit_text = j.build.unit.to_string() + fault_text(j.build.faults);
        if (!origin.empty()) j.rec.unit_text += "  (" + origin + ")";
        std::ofstream(j.unit_path) << config_to_json(j.build.unit) << '\n';
        FrameOptions fo;
        fo.base = j.build.unit;
        fo.fixed_unit = true;
        if (is_random_scene(spec.scene)) {
          // The co-simulation's random stream for this unit and seed, saved like a scene's.
          const CommandStream s = random_stream(
              j.build.unit, scenario_by_name(random_scenario(spec.scene)).shape, spec.seed);
          for (const auto& cmd : s.commands) {
            if (const auto* span = std::get_if<SpanCmd>(&cmd))
              j.rec.pixels += static_cast<uint64_t>(span->length);
          }
          s.save(j.rec.stream);
        } else {
          try {
            const PreparedFrame f = prepare_frame(from_base(base, spec.scene), fo);
            j.rec.pixels = f.encoded.stats.pixels;
            if (j.build.unit.specular.kind == SpecularUnitKind::kIdeal &&
                has_highlights(f.encoded.stream)) {
              j.rec.status = "skipped";
              j.rec.message = "configuration " + spec.config +
                              " has no specular hardware (the ideal unit's RTL slot outputs 0) "
                              "and the scene has highlights: its pixels cannot match the model";
            } else {
              f.encoded.stream.save(j.rec.stream);
            }
          } catch (const std::invalid_argument& e) {
            j.rec.status = "skipped";  // the scene needs more than this build has (lights,
                                       // channels, coordinates)
            j.rec.message = e.what();
          }
        }
        if (j.rec.status == "pending" && !netlists) {
          prefetch.add(j.build, parse_cosim_backend(spec.backend),
                       build_optimization(o, expected_cycles(j.rec.pixels)));
        }
      } catch (const std::exception& e) {
        j.rec.status = "error";
        j.rec.message = std::string("host setup failed: ") + e.what();
      }
    }
    if (j.rec.status != "pending") save_record(j);
    jobs.push_back(j);
  }
  return jobs;
}

// Runs `work(i)` for i in [0, n) on `workers` threads.
template <typename F>
void parallel_for(size_t n, int workers, F work) {
  std::atomic<size_t> next{0};
  std::vector<std::thread> pool;
  pool.reserve(static_cast<size_t>(std::max(workers, 0)));
  for (int w = 0; w < workers; ++w) {
    pool.emplace_back([&]() {
      for (size_t i = next++; i < n; i = next++) work(i);
    });
  }
  for (auto& t : pool) t.join();
}

// Every (configuration, backend) the pending jobs need, built once; a job whose build failed is
// an error (recorded at once).
void build_all(std::vector<Job>& jobs, const RegressOptions& o, int workers) {
  struct Need {
    RtlConfig build;
    CosimBackend backend;
    std::string key, executable, error;
    uint64_t cycles = 0;  // an upper estimate of what its runs simulate
  };
  std::vector<Need> needs;
  for (auto& j : jobs) {
    if (j.rec.status != "pending") continue;
    const CosimBackend be = parse_cosim_backend(j.spec.backend);
    const std::string key = rtl_build_key(j.build, be, o.coverage, o.cache);
    auto it = std::find_if(needs.begin(), needs.end(), [&](const Need& n) { return n.key == key; });
    if (it == needs.end()) it = needs.insert(needs.end(), {j.build, be, key, "", "", 0});
    it->cycles += expected_cycles(j.rec.pixels);
  }
  std::cout << "regress: " << needs.size() << " RTL build(s) needed (cache: "
            << (o.cache.empty() ? default_rtl_cache_dir() : o.cache) << ")" << std::endl;
  // Fewer builds than workers: each build's compiler runs on the spare cores.
  const int per_build =
      std::max<int>(1, workers / std::max<int>(1, static_cast<int>(needs.size())));
  parallel_for(needs.size(), workers, [&](size_t i) {
    try {
      RtlBuildOptions b = build_options(o);
      b.make_jobs = per_build;
      b.optimization = build_optimization(o, needs[i].cycles);
      needs[i].executable = ensure_rtl_build(needs[i].build, needs[i].backend, b).executable;
    } catch (const std::exception& e) {
      needs[i].error = e.what();
    }
  });
  for (auto& j : jobs) {
    if (j.rec.status != "pending") continue;
    const std::string key =
        rtl_build_key(j.build, parse_cosim_backend(j.spec.backend), o.coverage, o.cache);
    const auto it =
        std::find_if(needs.begin(), needs.end(), [&](const Need& n) { return n.key == key; });
    if (!it->error.empty()) {
      j.rec.status = "error";
      j.rec.message = "RTL build failed: " + it->error;
      save_record(j);
      continue;
    }
    j.executable = it->executable;
  }
}

// A field of a result file, or `fallback` when it is absent or null.
template <typename T>
T field(const nlohmann::json& j, const char* key, T fallback) {
  if (!j.is_object() || !j.contains(key) || j.at(key).is_null()) return fallback;
  try {
    return j.at(key).get<T>();
  } catch (const nlohmann::json::exception&) {
    return fallback;
  }
}

// Runs one job's co-simulation as a child process; fills its record from the child's JSON.
// The co-simulation child's command line for one run: its unit, stream, stimulus, outputs.
std::vector<std::string> cosim_child_args(const Job& job, const RegressOptions& o,
                                          const RunSettings& settings, const fs::path& dir,
                                          const fs::path& result_path) {
  std::vector<std::string> args = {job.executable,
                                   "--unit",
                                   job.unit_path,
                                   "--config",
                                   job.spec.config,
                                   "--stream",
                                   job.rec.stream,
                                   "--seed",
                                   std::to_string(job.spec.seed),
                                   "--gap-pct",
                                   std::to_string(settings.gap_pct),
                                   "--max-gap",
                                   std::to_string(settings.max_gap),
                                   "--stall-pct",
                                   std::to_string(settings.stall_pct),
                                   "--save-dir",
                                   (dir / "failing").string()};
  if (settings.watchdog > 0)
    args.insert(args.end(), {"--watchdog", std::to_string(settings.watchdog)});
  if (!settings.fault.empty()) args.insert(args.end(), {"--fault", settings.fault});
  args.insert(args.end(), {"--replay-prefix", cosim_replay_prefix(job.spec.backend, o.cache,
                                                                  o.netlist, o.netlist_cache)});
  if (o.coverage) {
    // Written by the run itself, pass or fail; a resumed run must not keep an earlier attempt's.
    const fs::path dat = dir / "coverage.dat";
    fs::remove(dat);
    args.insert(args.end(), {"--coverage", dat.string()});
  }
  args.insert(args.end(), {"--json", result_path.string()});
  return args;
}

// A mismatching C++ run is re-run on a traced build to draw the failing window (--waves).
void record_waves(const Job& job, const RegressOptions& o, const RunSettings& settings,
                  std::vector<std::string> args, RunRecord& rec) {
  const fs::path dir(rec.dir);
  const fs::path fst = dir / "waves.fst";
  RtlBuildOptions traced = build_options(o);
  traced.coverage = false;  // the traced re-run only draws the window; its coverage is the run's
  args[0] = ensure_rtl_build(job.build, CosimBackend::kCppTrace, traced).executable;
  const auto cov = std::find(args.begin(), args.end(), "--coverage");
  if (cov != args.end()) args.erase(cov, cov + 2);
  args.back() = (dir / "waves.json").string();
  args.push_back("--waves");
  args.push_back(fst.string());
  run_process(args, (dir / "waves.log").string(), settings.timeout);
  if (fs::exists(fst)) rec.waves = fst.string();
}

void run_job(Job& job, const RegressOptions& o, const RunSettings& settings) {
  RunRecord& rec = job.rec;
  const fs::path dir(rec.dir);
  const fs::path result_path = dir / "cosim.json";
  fs::remove(result_path);  // a resumed run must not read the result of an earlier attempt
  rec.log = (dir / "cosim.log").string();
  const std::vector<std::string> args = cosim_child_args(job, o, settings, dir, result_path);
  // The children are SystemC programs too: keep their logs free of its banner; their replay
  // lines name the stream, which carries its unit.
  const auto t0 = std::chrono::steady_clock::now();
  const ProcessResult r = run_process(args, rec.log, settings.timeout);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (r.timed_out) {
    rec.status = "timeout";
    rec.seconds = wall;
    rec.message =
        "killed after " + number_text(settings.timeout) + " s (--timeout); log: " + rec.log;
    rec.replay = replay_command(job, settings, o);
    return;
  }
  nlohmann::json j;
  try {
    std::ifstream is(result_path);
    if (is) j = nlohmann::json::parse(is);
  } catch (const nlohmann::json::exception&) {
    j = nlohmann::json();
  }
  rec.cycles = field(j, "cycles", uint64_t{0});
  rec.seconds = field(j, "seconds", 0.0);
  rec.cycles_per_second = field(j, "cycles_per_second", 0.0);
  rec.replay = field(j, "replay", std::string());
  // A run that shaded nothing compared nothing: it is not a pass (the co-simulation
  // exits 1 for it, with no mismatch to name).
  if ((r.exit_code == 0 || r.exit_code == 1) && field(j, "passed", false) &&
      (rec.cycles == 0 || field(j, "pixels", uint64_t{0}) == 0)) {
    rec.status = "error";
    rec.message = "the run shaded " + std::to_string(field(j, "pixels", uint64_t{0})) +
                  " pixels in " + std::to_string(rec.cycles) +
                  " cycles: nothing was compared (an empty image?), so it does not count as a pass";
    return;
  }
  if (r.exit_code == 0 && field(j, "passed", false)) {
    rec.status = "pass";
    return;
  }
  if (r.exit_code == 1 && j.is_object()) {
    const nlohmann::json first = field(j, "first_mismatch", nlohmann::json::object());
    rec.status = field(first, "kind", std::string()) == "hang" ? "hang" : "mismatch";
    rec.message = field(first, "message", std::string("mismatch (the result names none)"));
    if (o.waves && job.spec.backend == "cpp") record_waves(job, o, settings, args, rec);
    return;
  }
  rec.status = "error";
  if (rec.replay.empty()) rec.replay = replay_command(job, settings, o);
  // The last non-empty line of the log says why; the whole log is kept beside the results.
  std::ifstream log(rec.log);
  std::string line, last;
  while (std::getline(log, line)) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  }
  rec.message = "co-simulation exited with " + std::to_string(r.exit_code) + ": " + last +
                " (log: " + rec.log + ")";
}

// Runs the pending jobs; each writes its record the moment it ends, so a killed regression keeps
// every finished run.
void run_jobs(std::vector<Job>& jobs, const RegressOptions& o, const RunSettings& settings,
              int workers) {
  std::atomic<size_t> done{0};
  std::mutex print_mutex;
  parallel_for(jobs.size(), workers, [&](size_t i) {
    Job& j = jobs[i];
    if (j.rec.status == "pending") {
      if (InterruptGuard::requested()) {
        j.rec.status = "interrupted";
        j.rec.message = "not run: the regression got signal " +
                        std::to_string(InterruptGuard::signal_number()) +
                        " before it started (--resume runs it)";
      } else {
        try {
          run_job(j, o, settings);
        } catch (const std::exception& e) {
          j.rec.status = "error";
          j.rec.message = e.what();
        }
        // A run that failed after the signal (which reaches the simulator too) was stopped by
        // it, not by the RTL.
        if (j.rec.status != "pass" && InterruptGuard::requested()) {
          j.rec.message = "stopped by signal " + std::to_string(InterruptGuard::signal_number()) +
                          " (--resume runs it again): " + j.rec.message;
          j.rec.status = "interrupted";
        }
      }
      try {
        save_record(j);
      } catch (const std::exception& e) {
        j.rec.status = "error";
        j.rec.message += std::string(" (and its record could not be written: ") + e.what() + ")";
      }
    }
    const size_t n = ++done;
    const RunRecord& r = j.rec;
    std::lock_guard<std::mutex> lock(print_mutex);
    std::cout << "[" << n << "/" << jobs.size() << "] " << r.spec.id() << ": " << r.status << ", "
              << r.cycles << " cycles, " << fixed_text(r.seconds, 2) << " s";
    if (r.status != "pass")
      std::cout << "\n    " << r.message << (r.replay.empty() ? "" : "\n    replay: " + r.replay);
    if (!r.waves.empty()) std::cout << "\n    waves: " << r.waves;
    std::cout << std::endl;
  });
}

void list_named_builds() {
  for (const auto& c : load_named_builds(named_builds_path())) {
    std::string backends;
    for (const auto& b : c.backends) backends += (backends.empty() ? "" : ",") + b;
    std::cout << std::left << std::setw(18) << c.name << std::setw(13) << backends
              << c.unit.to_string() << (c.faults.any() ? "  (injected fault)" : "") << '\n';
  }
}

// Every run's record, the earlier ones (--resume) first, in job-list order.
std::vector<RunRecord> collect_records(const std::vector<RunRecord>& earlier,
                                       const std::vector<Job>& jobs) {
  std::vector<RunRecord> records = earlier;
  for (const auto& j : jobs) records.push_back(j.rec);
  sort_records(records);
  check_backends_agree(records);
  return records;
}

// The table, the counts and the --junit / --json files.
RunCounts report_runs(const std::vector<RunRecord>& records, const RegressOptions& o, double wall,
                      int workers) {
  print_run_table(records);
  const RunCounts c = count_runs(records);
  std::cout << "\nregress: " << c.passed << " passed, " << c.mismatched << " mismatched, "
            << c.hangs << " hung, " << c.timeouts << " timed out, " << c.errors << " error(s), "
            << (c.interrupted > 0 ? std::to_string(c.interrupted) + " interrupted, " : "")
            << c.skipped << " skipped (the scene does not fit the configuration) in "
            << fixed_text(wall, 1) << " s with " << workers << " job(s)\n";
  for (const auto& r : records) {
    if (r.status == "skipped")
      std::cout << "  skipped " << r.scene_name << " x " << r.spec.config << ": " << r.message
                << '\n';
  }
  if (!o.junit_path.empty()) write_junit_report(o.junit_path, records);
  return c;
}

}  // namespace

int run_regress(const RegressOptions& o) {
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
  if (o.list) {
    list_named_builds();
    return 0;
  }
  for (const auto& b : o.backends) {
    if (b != "cpp" && b != "systemc")
      throw std::invalid_argument("--backends: '" + b + "': expected cpp or systemc");
  }
  const int workers =
      std::max(1, o.jobs > 0 ? o.jobs : static_cast<int>(std::thread::hardware_concurrency()));

  // Select configurations and scenes; a new plan is written down (or handed out as job lines).
  const Selection sel = o.resume.empty() ? select_planned(o) : select_resumed(o);
  if (!o.emit_jobs.empty()) {
    emit_job_lines(o, sel.settings, sel.out, sel.all, sel.selected);
    return 0;
  }
  if (o.resume.empty()) write_and_announce_plan(o, sel);
  print_settings(sel, o.coverage);

  // Host setup, build, run: each run's record is on disk the moment it ends.
  RtlPrefetch prefetch(build_options(o), workers);
  std::unique_ptr<NetlistSource> netlists;
  if (o.netlist) netlists = std::make_unique<NetlistSource>(o, workers);
  std::vector<Job> jobs =
      plan_jobs(sel.selected, sel.out, sel.base, prefetch, netlists.get(), o, sel.settings);
  if (netlists) resolve_netlists(jobs, *netlists);
  const auto t0 = std::chrono::steady_clock::now();
  const InterruptGuard interrupt;  // Ctrl-C: no new runs; the rest are recorded as interrupted
  build_all(jobs, o, workers);
  run_jobs(jobs, o, sel.settings, workers);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Collect, report, exit code.
  const std::vector<RunRecord> records = collect_records(sel.earlier, jobs);
  const RunCounts c = report_runs(records, o, wall, workers);
  nlohmann::json coverage = nullptr;
  const bool coverage_met = !o.coverage || report_coverage(records, sel.out, o, &coverage);
  if (!o.json_path.empty()) {
    write_json_report(o.json_path, records,
                      {{"seed", o.seed}, {"wall_seconds", wall}, {"coverage", coverage}});
  }

  if (InterruptGuard::requested()) {
    std::cout << "regress: interrupted by signal " << InterruptGuard::signal_number() << ": "
              << c.interrupted << " run(s) recorded as interrupted; run them with: " << self_path()
              << " regress --resume " << shell_word(sel.out.string()) << std::endl;
    return 128 + InterruptGuard::signal_number();
  }
  if (c.passed == 0 && !c.failed()) {
    std::cout << "regress: FAIL: no run was executed\n";
    return 1;
  }
  return c.failed() || !coverage_met ? 1 : 0;
}

}  // namespace shadesim
