// shadesim regress: the main job. Every scene x configuration x simulation backend: the host
// encodes the scene for the configuration's unit, shadesim builds the configuration's RTL on
// demand (sim/rtl_build.h) and its co-simulation executable replays the stream against the
// bit-accurate model and the cycle model; this command collects, tabulates and reports.
//
// By default each scene runs on its own configuration (the smallest unit that shades it); the
// named builds (sim/harness/builds.json) with --configs, any other unit with --config FILE.json.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include <cstdlib>

#include "host/frame.h"
#include "host/scene_config.h"
#include "sim/commands.h"
#include "sim/junit.h"
#include "sim/process.h"
#include "sim/rtl_build.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

struct RegressOptions {
  std::vector<std::string> scenes;
  std::vector<std::string> configs;       // named builds (--configs)
  std::vector<std::string> config_files;  // UnitConfig files (--config)
  std::vector<std::string> backends{"cpp", "systemc"};
  uint64_t seed = 1;
  int jobs = 0;  // 0: hardware threads
  int gap_pct = 20, max_gap = 8, stall_pct = 20;
  std::string out_dir = "out/regress";
  std::string junit_path;
  std::string json_path;
  std::string cache;
  bool waves = false;
  bool list = false;
};

struct Job {
  std::string scene;       // path
  std::string scene_name;  // stem
  std::string config;      // the configuration's name in reports
  RtlConfig build;
  std::string backend;
  std::string executable;  // the build's co-simulation executable
  std::string unit_path;   // the unit as JSON, for --unit
  std::string stream_path;
  uint64_t seed = 0;
  uint64_t pixels = 0;
  // Filled in by the run.
  std::string status = "pending";  // pass | mismatch | error | skipped
  std::string message;
  uint64_t cycles = 0;
  double seconds = 0;
  double cycles_per_second = 0;
  std::string replay;
  std::string log_path;
  std::string waves_path;
};

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

// A configuration's name as part of a file name: a config file's path ("out/x/chosen.json") has
// folders in it.
std::string file_label(const std::string& config) {
  std::string s = config;
  if (fs::path(s).extension() == ".json") s = fs::path(s).stem().string();
  for (char& c : s) {
    if (c == '/' || c == ':' || c == ' ') c = '_';
  }
  return s;
}

RtlBuildOptions build_options(const RegressOptions& o) {
  RtlBuildOptions b;
  b.cache_dir = o.cache;
  b.make_jobs = 1;  // builds run side by side
  return b;
}

// Runs one job's co-simulation as a child process; fills status and figures from its JSON.
void run_job(Job& job, const RegressOptions& o, const fs::path& out) {
  const std::string base = job.scene_name + "__" + file_label(job.config) + "__" + job.backend;
  const fs::path result_path = out / "results" / (base + ".json");
  job.log_path = (out / "logs" / (base + ".log")).string();
  std::vector<std::string> args = {job.executable,
                                   "--unit", job.unit_path,
                                   "--config", job.config,
                                   "--stream", job.stream_path,
                                   "--seed", std::to_string(job.seed),
                                   "--gap-pct", std::to_string(o.gap_pct),
                                   "--max-gap", std::to_string(o.max_gap),
                                   "--stall-pct", std::to_string(o.stall_pct),
                                   "--save-dir", (out / "failing").string(),
                                   "--json", result_path.string()};
  // The children are SystemC programs too: keep their logs free of its banner; their replay
  // lines name the stream, which carries its unit.
  const ProcessResult r = run_process(args, job.log_path);
  nlohmann::json j;
  try {
    std::ifstream is(result_path);
    if (is) j = nlohmann::json::parse(is);
  } catch (const nlohmann::json::exception&) {
    j = nlohmann::json();
  }
  job.cycles = field(j, "cycles", uint64_t{0});
  job.seconds = field(j, "seconds", 0.0);
  job.cycles_per_second = field(j, "cycles_per_second", 0.0);
  job.replay = field(j, "replay", std::string());
  if (r.exit_code == 0 && field(j, "passed", false)) {
    job.status = "pass";
    return;
  }
  if (r.exit_code == 1 && j.is_object()) {
    job.status = "mismatch";
    job.message = field(field(j, "first_mismatch", nlohmann::json::object()), "message",
                        std::string("mismatch (the result names none)"));
    if (o.waves && job.backend == "cpp") {
      const fs::path fst = out / "waves" / (base + ".fst");
      args[0] = ensure_rtl_build(job.build, CosimBackend::kCppTrace, build_options(o)).executable;
      args.back() = (out / "results" / (base + ".waves.json")).string();
      args.push_back("--waves");
      args.push_back(fst.string());
      run_process(args, (out / "logs" / (base + ".waves.log")).string());
      if (fs::exists(fst)) job.waves_path = fst.string();
    }
    return;
  }
  job.status = "error";
  // The last non-empty line of the log says why; the whole log is kept beside the results.
  std::ifstream log(job.log_path);
  std::string line, last;
  while (std::getline(log, line)) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  }
  job.message = "co-simulation exited with " + std::to_string(r.exit_code) + ": " + last + " (log: " + job.log_path + ")";
}

std::string fmt(double v, int precision) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(precision) << v;
  return os.str();
}

// Column width: the longest entry (at least the header), so long names never run together.
template <typename F>
int column_width(const std::vector<Job>& jobs, const std::string& header, F get) {
  size_t w = header.size();
  for (const auto& j : jobs) w = std::max(w, get(j).size());
  return static_cast<int>(w + 2);
}

void print_table(const std::vector<Job>& jobs) {
  const int ws = column_width(jobs, "scene", [](const Job& j) { return j.scene_name; });
  const int wc = column_width(jobs, "config", [](const Job& j) { return j.config; });
  std::cout << '\n'
            << std::left << std::setw(ws) << "scene" << std::setw(wc) << "config" << std::setw(9) << "backend"
            << std::right << std::setw(9) << "pixels" << std::setw(11) << "cycles" << std::setw(8) << "cyc/px"
            << std::setw(10) << "result" << std::setw(9) << "wall s" << std::setw(11) << "Mcycles/s" << '\n';
  for (const auto& j : jobs) {
    // Only a completed run has a cycle count; a mismatch stops the run where it is found.
    const bool complete = j.status == "pass";
    std::cout << std::left << std::setw(ws) << j.scene_name << std::setw(wc) << j.config << std::setw(9) << j.backend
              << std::right << std::setw(9) << j.pixels << std::setw(11) << (complete ? std::to_string(j.cycles) : "-")
              << std::setw(8)
              << (complete && j.pixels ? fmt(static_cast<double>(j.cycles) / static_cast<double>(j.pixels), 3) : "-")
              << std::setw(10) << j.status << std::setw(9) << fmt(j.seconds, 2) << std::setw(11)
              << (complete ? fmt(j.cycles_per_second / 1e6, 2) : "-") << '\n';
  }
  // What each configuration is.
  std::vector<std::string> seen;
  std::cout << "\nconfigurations:\n";
  for (const auto& j : jobs) {
    if (std::find(seen.begin(), seen.end(), j.config) != seen.end()) continue;
    seen.push_back(j.config);
    std::cout << "  " << std::left << std::setw(wc) << j.config << j.build.unit.to_string()
              << fault_text(j.build.faults) << '\n';
  }
}

// The scene's own configuration: the smallest unit that shades it within its error budget, with
// real specular hardware (host/scene_config.h states each rule).
RtlConfig own_config(const std::string& scene) {
  RtlConfig c;
  c.name = "own:" + fs::path(scene).stem().string();
  c.unit = derive_config({scene}, DeriveOptions{}).config;
  return c;
}

// Whether any material of the stream lights a specular term (a build with no specular hardware
// cannot match the model there).
bool has_highlights(const CommandStream& stream) {
  for (const auto& cmd : stream.commands) {
    if (const auto* m = std::get_if<MaterialCmd>(&cmd)) {
      for (auto v : m->spec_colour) if (v != 0) return true;
    }
  }
  return false;
}

std::vector<std::string> default_scenes() {
  // Run from the project folder, the shipped scenes are ./scenes; elsewhere, the checkout's.
  fs::path dir = "scenes";
  if (!fs::is_directory(dir)) dir = fs::path(source_dir()) / "scenes";
  if (!fs::is_directory(dir)) {
    throw std::invalid_argument("regress: no scene files given, and neither ./scenes nor " + dir.string() +
                                " exists; name scene files, or run from the project folder");
  }
  std::vector<std::string> scenes;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() == ".json") scenes.push_back(e.path().string());
  }
  std::sort(scenes.begin(), scenes.end());
  if (scenes.empty()) throw std::invalid_argument("regress: no scenes given and none in " + dir.string());
  return scenes;
}

// The configurations every scene runs on: the named (--configs) and file (--config) ones. Empty:
// each scene on its own.
std::vector<RtlConfig> chosen_configs(const RegressOptions& o) {
  std::vector<RtlConfig> configs;
  for (const auto& name : o.configs) configs.push_back(named_build(named_builds_path(), name));
  for (const auto& file : o.config_files) configs.push_back(resolve_rtl_config(file, "--config"));
  return configs;
}

// Host side: encode each scene for each configuration and save the stream. One scene and
// configuration at a time (mesh import limits the process's address space while it runs, so it
// is not done on several threads at once).
void plan_jobs(const RegressOptions& o, const std::vector<std::string>& scenes, const fs::path& out,
               std::vector<Job>& jobs, std::vector<Job>& skipped) {
  const std::vector<RtlConfig> fixed = chosen_configs(o);
  uint64_t job_seed = o.seed;
  for (const auto& scene : scenes) {
    std::vector<RtlConfig> configs = fixed;
    if (configs.empty()) configs.push_back(own_config(scene));
    for (const auto& c : configs) {
      Job proto;
      proto.scene = scene;
      proto.scene_name = fs::path(scene).stem().string();
      proto.config = c.name;
      proto.build = c;
      const std::string safe = file_label(c.name);
      auto skip = [&](const std::string& why) {
        proto.status = "skipped";
        proto.message = why;
        for (const auto& b : o.backends) {
          proto.backend = b;
          skipped.push_back(proto);
        }
      };
      FrameOptions fo;
      fo.base = c.unit;
      fo.fixed_unit = true;
      try {
        const PreparedFrame f = prepare_frame(scene, fo);
        if (c.unit.specular.kind == SpecularUnitKind::kIdeal && has_highlights(f.encoded.stream)) {
          skip("configuration " + c.name + " has no specular hardware (the ideal unit's RTL slot outputs 0) "
               "and the scene has highlights: its pixels cannot match the model");
          continue;
        }
        proto.stream_path = (out / "streams" / (proto.scene_name + "__" + safe + ".cmds")).string();
        f.encoded.stream.save(proto.stream_path);
        proto.pixels = f.encoded.stats.pixels;
      } catch (const std::invalid_argument& e) {
        skip(e.what());  // the scene needs more than this build has (lights, channels, coordinates)
        continue;
      }
      for (const auto& b : o.backends) {
        Job j = proto;
        j.backend = b;
        j.seed = job_seed;
        jobs.push_back(j);
      }
      ++job_seed;
    }
  }
}

// Runs `work(i)` for i in [0, n) on `workers` threads.
template <typename F>
void parallel_for(size_t n, int workers, F work) {
  std::atomic<size_t> next{0};
  std::vector<std::thread> pool;
  for (int w = 0; w < workers; ++w) {
    pool.emplace_back([&]() {
      for (size_t i = next++; i < n; i = next++) work(i);
    });
  }
  for (auto& t : pool) t.join();
}

// Every (configuration, backend) the jobs need, built once; a job whose build failed is an error.
void build_all(std::vector<Job>& jobs, const RegressOptions& o, const fs::path& out, int workers) {
  struct Need {
    RtlConfig build;
    CosimBackend backend;
    std::string key, executable, error;
  };
  std::vector<Need> needs;
  for (auto& j : jobs) {
    const CosimBackend be = parse_cosim_backend(j.backend);
    const std::string key = rtl_build_key(j.build, be);
    if (std::none_of(needs.begin(), needs.end(), [&](const Need& n) { return n.key == key; })) {
      needs.push_back({j.build, be, key, "", ""});
    }
  }
  std::cout << "regress: " << needs.size() << " RTL build(s) needed (cache: "
            << (o.cache.empty() ? default_rtl_cache_dir() : o.cache) << ")" << std::endl;
  parallel_for(needs.size(), workers, [&](size_t i) {
    try {
      needs[i].executable = ensure_rtl_build(needs[i].build, needs[i].backend, build_options(o)).executable;
    } catch (const std::exception& e) {
      needs[i].error = e.what();
    }
  });
  fs::create_directories(out / "units");
  for (auto& j : jobs) {
    const std::string key = rtl_build_key(j.build, parse_cosim_backend(j.backend));
    const auto it = std::find_if(needs.begin(), needs.end(), [&](const Need& n) { return n.key == key; });
    if (!it->error.empty()) {
      j.status = "error";
      j.message = "RTL build failed: " + it->error;
      continue;
    }
    j.executable = it->executable;
    j.unit_path = (out / "units" / (file_label(j.config) + ".json")).string();
    std::ofstream(j.unit_path) << config_to_json(j.build.unit) << '\n';
  }
}

void run_jobs(std::vector<Job>& jobs, const RegressOptions& o, const fs::path& out, int workers) {
  std::atomic<size_t> done{0};
  std::mutex print_mutex;
  parallel_for(jobs.size(), workers, [&](size_t i) {
    Job& j = jobs[i];
    if (j.status == "pending") {
      try {
        run_job(j, o, out);
      } catch (const std::exception& e) {
        j.status = "error";
        j.message = e.what();
      }
    }
    const size_t n = ++done;
    std::lock_guard<std::mutex> lock(print_mutex);
    std::cout << "[" << n << "/" << jobs.size() << "] " << j.scene_name << " x " << j.config << " (" << j.backend
              << "): " << j.status << ", " << j.cycles << " cycles, " << fmt(j.seconds, 2) << " s";
    if (j.status != "pass") std::cout << "\n    " << j.message << (j.replay.empty() ? "" : "\n    replay: " + j.replay);
    if (!j.waves_path.empty()) std::cout << "\n    waves: " << j.waves_path;
    std::cout << std::endl;
  });
}

// Both backends simulate the same RTL on the same stimulus: their cycle counts must agree.
void check_backends_agree(std::vector<Job>& jobs) {
  for (size_t a = 0; a < jobs.size(); ++a) {
    for (size_t b = a + 1; b < jobs.size(); ++b) {
      if (jobs[a].scene == jobs[b].scene && jobs[a].config == jobs[b].config && jobs[a].status == "pass" &&
          jobs[b].status == "pass" && jobs[a].cycles != jobs[b].cycles) {
        jobs[b].status = "mismatch";
        jobs[b].message = "backends disagree: " + jobs[a].backend + " " + std::to_string(jobs[a].cycles) +
                          " cycles, " + jobs[b].backend + " " + std::to_string(jobs[b].cycles);
      }
    }
  }
}

void write_junit_report(const std::string& path, const std::vector<Job>& jobs) {
  JUnitSuite suite{"shadesim.regress", {}};
  for (const auto& j : jobs) {
    JUnitCase c;
    c.classname = "regress." + j.scene_name;
    c.name = j.config + "." + j.backend;
    c.seconds = j.seconds;
    if (j.status == "mismatch" || j.status == "error") {
      c.failure = j.message + (j.replay.empty() ? "" : "\nreplay: " + j.replay);
    } else if (j.status == "skipped") {
      c.skipped = j.message;
    }
    suite.cases.push_back(c);
  }
  write_junit(path, suite);
}

void write_json_report(const std::string& path, const RegressOptions& o, const std::vector<Job>& jobs,
                       const nlohmann::json& totals) {
  nlohmann::json all = nlohmann::json::array();
  for (const auto& j : jobs) {
    all.push_back({{"scene", j.scene}, {"config", j.config},
                   {"unit", nlohmann::json::parse(config_to_json(j.build.unit))},
                   {"backend", j.backend}, {"status", j.status},
                   {"pixels", j.pixels}, {"cycles", j.cycles},
                   {"cycles_per_pixel", j.pixels ? static_cast<double>(j.cycles) / static_cast<double>(j.pixels) : 0.0},
                   {"seconds", j.seconds}, {"cycles_per_second", j.cycles_per_second}, {"seed", j.seed},
                   {"message", j.message}, {"replay", j.replay}, {"stream", j.stream_path}, {"log", j.log_path},
                   {"waves", j.waves_path}});
  }
  nlohmann::json doc = totals;
  doc["seed"] = o.seed;
  doc["jobs"] = all;
  std::ofstream os(path);
  if (!os) throw std::runtime_error(path + ": cannot open for writing");
  os << doc.dump(2) << '\n';
}

void list_named_builds() {
  for (const auto& c : load_named_builds(named_builds_path())) {
    std::string backends;
    for (const auto& b : c.backends) backends += (backends.empty() ? "" : ",") + b;
    std::cout << std::left << std::setw(18) << c.name << std::setw(13) << backends << c.unit.to_string()
              << (c.faults.any() ? "  (injected fault)" : "") << '\n';
  }
}

int run_regress(const RegressOptions& o) {
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
  if (o.list) {
    list_named_builds();
    return 0;
  }
  for (const auto& b : o.backends) {
    if (b != "cpp" && b != "systemc") throw std::invalid_argument("--backends: '" + b + "': expected cpp or systemc");
  }
  const std::vector<std::string> scenes = o.scenes.empty() ? default_scenes() : o.scenes;
  const fs::path out(o.out_dir);
  for (const char* sub : {"streams", "results", "logs", "failing", "waves"}) fs::create_directories(out / sub);
  const int workers = std::max(1, o.jobs > 0 ? o.jobs : static_cast<int>(std::thread::hardware_concurrency()));
  const bool own = o.configs.empty() && o.config_files.empty();
  std::cout << "regress: seed " << o.seed << ", " << scenes.size() << " scene(s) x "
            << (own ? std::string("its own configuration") : std::to_string(o.configs.size() + o.config_files.size()) +
                                                                 " configuration(s)")
            << " x " << o.backends.size() << " backend(s); stimulus gap " << o.gap_pct << "% (max " << o.max_gap
            << "), back-pressure " << o.stall_pct << "%" << std::endl;

  std::vector<Job> jobs, skipped;
  plan_jobs(o, scenes, out, jobs, skipped);
  const auto t0 = std::chrono::steady_clock::now();
  build_all(jobs, o, out, workers);
  run_jobs(jobs, o, out, workers);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  check_backends_agree(jobs);
  jobs.insert(jobs.end(), skipped.begin(), skipped.end());

  print_table(jobs);
  const auto count = [&](const char* s) {
    return std::count_if(jobs.begin(), jobs.end(), [&](const Job& j) { return j.status == s; });
  };
  const long passed = count("pass"), mismatched = count("mismatch"), errors = count("error"), skips = count("skipped");
  std::cout << "\nregress: " << passed << " passed, " << mismatched << " mismatched, " << errors << " error(s), "
            << skips << " skipped (the scene does not fit the configuration) in " << fmt(wall, 1) << " s with "
            << workers << " job(s); seed " << o.seed << '\n';
  for (const auto& j : jobs) {
    if (j.status == "skipped") std::cout << "  skipped " << j.scene_name << " x " << j.config << ": " << j.message << '\n';
  }
  if (!o.junit_path.empty()) write_junit_report(o.junit_path, jobs);
  if (!o.json_path.empty()) {
    write_json_report(o.json_path, o, jobs,
                      {{"passed", passed}, {"mismatched", mismatched}, {"errors", errors}, {"skipped", skips},
                       {"wall_seconds", wall}});
  }
  if (passed == 0 && mismatched == 0 && errors == 0) {
    std::cout << "regress: FAIL: no run was executed\n";
    return 1;
  }
  return (mismatched > 0 || errors > 0) ? 1 : 0;
}

}  // namespace

void register_regress(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<RegressOptions>();
  CLI::App* sub = app.add_subcommand(
      "regress",
      "RTL regression, the main job: every scene x configuration x backend (Verilator C++ and\n"
      "Verilator-in-SystemC). By default each scene runs on its own configuration - the smallest\n"
      "unit that shades it (channels and lights as it needs; a scene naming the `ideal` unit, which\n"
      "has no hardware, gets the W_16 unit; `shadesim config --help` states each rule). --configs runs\n"
      "named builds (sim/harness/builds.json,\n"
      "see --list), --config any UnitConfig FILE.json. The RTL of each configuration is Verilated on\n"
      "demand into the build cache. Each run compares every pixel bit for bit with the bit-accurate\n"
      "model and every scanline's completion cycle with the cycle model, under seeded input gaps and\n"
      "output back-pressure. Exits 1 on any mismatch (naming it, with a replay command) and when no\n"
      "run was executed.");
  sub->add_option("scenes", o->scenes, "scene files (default: scenes/*.json)")->check(CLI::ExistingFile);
  sub->add_option("--configs", o->configs, "named builds to run every scene on (see --list)")
      ->delimiter(',')->allow_extra_args(false);
  sub->add_option("--config", o->config_files, "a UnitConfig FILE.json to run every scene on (repeatable)")
      ->allow_extra_args(false);
  sub->add_option("--backends", o->backends, "cpp, systemc or both (comma-separated)")
      ->delimiter(',')->allow_extra_args(false)->capture_default_str();
  sub->add_option("--seed", o->seed, "seed of the stimulus (printed on every run)")->capture_default_str();
  sub->add_option("-j,--jobs", o->jobs, "parallel builds and co-simulations (default: hardware threads)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--gap-pct", o->gap_pct, "chance of idle cycles before a command word")->check(CLI::Range(0, 100))->capture_default_str();
  sub->add_option("--max-gap", o->max_gap, "longest idle gap in cycles")->check(CLI::Range(1, 100000))->capture_default_str();
  sub->add_option("--stall-pct", o->stall_pct, "chance of output back-pressure per cycle")->check(CLI::Range(0, 99))->capture_default_str();
  sub->add_option("-o,--out", o->out_dir, "where streams, results, logs and waveforms go")->capture_default_str();
  sub->add_option("--junit", o->junit_path, "write JUnit XML for CI");
  sub->add_option("--json", o->json_path, "write every run's figures as JSON");
  sub->add_option("--cache", o->cache, "RTL build cache folder (default: <build>/rtl-cache)");
  sub->add_flag("--waves", o->waves, "on a mismatch, re-run the C++ backend with FST tracing of the window around it");
  sub->add_flag("--list", o->list, "list the named builds and exit");
  sub->callback([o, &exit_code]() { exit_code = run_regress(*o); });
}

}  // namespace shadesim
