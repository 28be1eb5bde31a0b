// shadesim regress: the main job. Every scene x every Verilated configuration x both simulation
// backends: the host encodes the scene for the configuration's unit, the co-simulation
// executables (rtl_cosim_cpp / rtl_cosim_sc, built by cmake/rtl.cmake) replay the stream against
// the bit-accurate model and the cycle model, and this command collects, tabulates and reports.
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
#include "sim/commands.h"
#include "sim/junit.h"
#include "sim/process.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

struct RegressOptions {
  std::vector<std::string> scenes;
  std::vector<std::string> configs;   // empty: every configuration without an injected fault
  std::vector<std::string> backends{"cpp", "systemc"};
  uint64_t seed = 1;
  int jobs = 0;  // 0: hardware threads
  int gap_pct = 20, max_gap = 8, stall_pct = 20;
  std::string out_dir = "out/regress";
  std::string junit_path;
  std::string json_path;
  std::string cosim_dir;
  bool waves = false;
  bool list = false;
};

struct CosimConfig {
  std::string name;
  UnitConfig unit;
  bool faulty = false;
  std::vector<std::string> backends;  // the executables this configuration is Verilated into
};

struct Job {
  std::string scene;       // path
  std::string scene_name;  // stem
  std::string config;
  std::string backend;
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

std::string executable(const std::string& dir, const std::string& backend, bool trace = false) {
  const std::string name = backend == "cpp" ? (trace ? "rtl_cosim_cpp_trace" : "rtl_cosim_cpp") : "rtl_cosim_sc";
  return (fs::path(dir) / name).string();
}

std::string find_cosim_dir(const std::string& requested) {
  std::vector<std::string> candidates;
  if (!requested.empty()) candidates.push_back(requested);
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(self.parent_path().string());
  candidates.push_back(SHADESIM_BINARY_DIR);
  for (const auto& c : candidates) {
    if (fs::exists(fs::path(c) / "rtl_cosim_cpp")) return c;
  }
  throw std::runtime_error(
      "regress: co-simulation executables (rtl_cosim_cpp, rtl_cosim_sc) not found in " +
      (requested.empty() ? std::string("the build directory") : requested) +
      "; build with -DSHADESIM_RTL=ON (the default) or point --cosim-dir at them");
}

// Every configuration Verilated into either backend's executable, with the backends that have it.
std::vector<CosimConfig> list_configs(const std::string& cosim_dir) {
  std::vector<CosimConfig> configs;
  for (const std::string backend : {"cpp", "systemc"}) {
    const std::string exe = executable(cosim_dir, backend);
    if (!fs::exists(exe)) continue;
    const ProcessResult r = run_process({exe, "--list", "--json"}, "");
    if (r.exit_code != 0) {
      throw std::runtime_error("regress: '" + exe + " --list --json' failed (exit " + std::to_string(r.exit_code) +
                               "): " + r.output.substr(0, 400));
    }
    try {
      for (const auto& e : nlohmann::json::parse(r.output)) {
        const std::string name = e.at("name").get<std::string>();
        auto it = std::find_if(configs.begin(), configs.end(), [&](const CosimConfig& c) { return c.name == name; });
        if (it == configs.end()) {
          CosimConfig c;
          c.name = name;
          c.unit = config_from_json(e.at("unit").dump(), exe + " --list: " + name + ": ");
          const auto faults = e.contains("faults") ? e.at("faults") : nlohmann::json();
          c.faulty = !(faults.is_null() || faults.empty());
          configs.push_back(std::move(c));
          it = configs.end() - 1;
        }
        it->backends.push_back(backend);
      }
    } catch (const nlohmann::json::exception& e) {
      throw std::runtime_error("regress: cannot read the configuration list of " + exe + ": " + e.what());
    }
  }
  return configs;
}

// Runs one job's co-simulation as a child process; fills status and figures from its JSON.
void run_job(Job& job, const RegressOptions& o, const std::string& cosim_dir, const fs::path& out) {
  const std::string base = job.scene_name + "__" + job.config + "__" + job.backend;
  const fs::path result_path = out / "results" / (base + ".json");
  job.log_path = (out / "logs" / (base + ".log")).string();
  std::vector<std::string> args = {executable(cosim_dir, job.backend),
                                   "--config", job.config,
                                   "--stream", job.stream_path,
                                   "--seed", std::to_string(job.seed),
                                   "--gap-pct", std::to_string(o.gap_pct),
                                   "--max-gap", std::to_string(o.max_gap),
                                   "--stall-pct", std::to_string(o.stall_pct),
                                   "--save-dir", (out / "failing").string(),
                                   "--json", result_path.string()};
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
      args[0] = executable(cosim_dir, "cpp", true);
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

void print_table(const std::vector<Job>& jobs) {
  std::cout << '\n'
            << std::left << std::setw(18) << "scene" << std::setw(20) << "config" << std::setw(9) << "backend"
            << std::right << std::setw(9) << "pixels" << std::setw(11) << "cycles" << std::setw(8) << "cyc/px"
            << std::setw(10) << "result" << std::setw(9) << "wall s" << std::setw(11) << "Mcycles/s" << '\n';
  for (const auto& j : jobs) {
    // Only a completed run has a cycle count; a mismatch stops the run where it is found.
    const bool complete = j.status == "pass";
    std::cout << std::left << std::setw(18) << j.scene_name << std::setw(20) << j.config << std::setw(9) << j.backend
              << std::right << std::setw(9) << j.pixels << std::setw(11) << (complete ? std::to_string(j.cycles) : "-")
              << std::setw(8)
              << (complete && j.pixels ? fmt(static_cast<double>(j.cycles) / static_cast<double>(j.pixels), 3) : "-")
              << std::setw(10) << j.status << std::setw(9) << fmt(j.seconds, 2) << std::setw(11)
              << (complete ? fmt(j.cycles_per_second / 1e6, 2) : "-") << '\n';
  }
}

int run_regress(const RegressOptions& o) {
  // The children are SystemC programs too: keep their logs free of its banner.
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
  const std::string cosim_dir = find_cosim_dir(o.cosim_dir);
  std::vector<CosimConfig> configs = list_configs(cosim_dir);
  if (o.list) {
    for (const auto& c : configs) {
      std::string backends;
      for (const auto& b : c.backends) backends += (backends.empty() ? "" : ",") + b;
      std::cout << std::left << std::setw(22) << c.name << std::setw(13) << backends << c.unit.to_string()
                << (c.faulty ? "  (injected fault)" : "") << '\n';
    }
    return 0;
  }
  if (!o.configs.empty()) {
    std::vector<CosimConfig> chosen;
    for (const auto& name : o.configs) {
      const auto it = std::find_if(configs.begin(), configs.end(), [&](const CosimConfig& c) { return c.name == name; });
      if (it == configs.end()) {
        std::string names;
        for (const auto& c : configs) names += (names.empty() ? "" : ", ") + c.name;
        throw std::invalid_argument("--configs: '" + name + "' is not a Verilated configuration; expected one of " + names);
      }
      chosen.push_back(*it);
    }
    configs = chosen;
  } else {
    // By default: the hardware builds. Injected-fault builds exist to prove the harness fails,
    // and an `ideal` build has no specular hardware (its slot outputs 0), so it cannot match
    // the model on a scene with highlights.
    configs.erase(std::remove_if(configs.begin(), configs.end(),
                                 [](const CosimConfig& c) {
                                   return c.faulty || c.unit.specular.kind == SpecularUnitKind::kIdeal;
                                 }),
                  configs.end());
    if (configs.empty()) {
      throw std::invalid_argument(
          "regress: no hardware configuration is built (only ideal or fault-injection builds); name one "
          "with --configs, see --list");
    }
  }
  for (const auto& b : o.backends) {
    if (b != "cpp" && b != "systemc") throw std::invalid_argument("--backends: '" + b + "': expected cpp or systemc");
  }
  std::vector<std::string> scenes = o.scenes;
  if (scenes.empty()) {
    for (const auto& e : fs::directory_iterator("scenes")) {
      if (e.path().extension() == ".json") scenes.push_back(e.path().string());
    }
    std::sort(scenes.begin(), scenes.end());
    if (scenes.empty()) throw std::invalid_argument("regress: no scenes given and none in ./scenes");
  }

  const fs::path out(o.out_dir);
  for (const char* sub : {"streams", "results", "logs", "failing", "waves"}) fs::create_directories(out / sub);
  std::cout << "regress: seed " << o.seed << ", " << scenes.size() << " scene(s) x " << configs.size()
            << " configuration(s) x " << o.backends.size() << " backend(s); stimulus gap " << o.gap_pct
            << "% (max " << o.max_gap << "), back-pressure " << o.stall_pct << "%\n";

  // Host side, one scene and configuration at a time (mesh import limits the process's address
  // space while it runs, so it is not done on several threads at once).
  std::vector<Job> jobs;
  std::vector<Job> skipped;
  uint64_t job_seed = o.seed;
  for (const auto& scene : scenes) {
    for (const auto& c : configs) {
      Job proto;
      proto.scene = scene;
      proto.scene_name = fs::path(scene).stem().string();
      proto.config = c.name;
      FrameOptions fo;
      fo.base = c.unit;
      fo.fixed_unit = true;
      try {
        const PreparedFrame f = prepare_frame(scene, fo);
        proto.stream_path = (out / "streams" / (proto.scene_name + "__" + c.name + ".cmds")).string();
        f.encoded.stream.save(proto.stream_path);
        proto.pixels = f.encoded.stats.pixels;
      } catch (const std::invalid_argument& e) {
        // The scene needs more than this build has (lights, channels, coordinate bits).
        proto.status = "skipped";
        proto.message = e.what();
        for (const auto& b : o.backends) {
          proto.backend = b;
          skipped.push_back(proto);
        }
        continue;
      }
      for (const auto& b : o.backends) {
        Job j = proto;
        j.backend = b;
        j.seed = job_seed;
        if (std::find(c.backends.begin(), c.backends.end(), b) == c.backends.end()) {
          j.status = "skipped";
          j.message = "configuration " + c.name + " is not Verilated into the " + b + " backend";
          skipped.push_back(j);
        } else {
          jobs.push_back(j);
        }
      }
      ++job_seed;
    }
  }

  // Co-simulation jobs in parallel, one child process each.
  const int workers = std::max(1, o.jobs > 0 ? o.jobs : static_cast<int>(std::thread::hardware_concurrency()));
  std::atomic<size_t> next{0};
  std::atomic<size_t> done{0};
  std::mutex print_mutex;
  const auto t0 = std::chrono::steady_clock::now();
  auto worker = [&]() {
    for (size_t i = next++; i < jobs.size(); i = next++) {
      try {
        run_job(jobs[i], o, cosim_dir, out);
      } catch (const std::exception& e) {
        jobs[i].status = "error";
        jobs[i].message = e.what();
      }
      const size_t n = ++done;
      std::lock_guard<std::mutex> lock(print_mutex);
      const Job& j = jobs[i];
      std::cout << "[" << n << "/" << jobs.size() << "] " << j.scene_name << " x " << j.config << " (" << j.backend
                << "): " << j.status << ", " << j.cycles << " cycles, " << fmt(j.seconds, 2) << " s";
      if (j.status != "pass") std::cout << "\n    " << j.message << (j.replay.empty() ? "" : "\n    replay: " + j.replay);
      if (!j.waves_path.empty()) std::cout << "\n    waves: " << j.waves_path;
      std::cout << std::endl;
    }
  };
  std::vector<std::thread> pool;
  for (int w = 0; w < workers; ++w) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Both backends simulate the same RTL on the same stimulus: their cycle counts must agree.
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
  jobs.insert(jobs.end(), skipped.begin(), skipped.end());
  print_table(jobs);
  const auto count = [&](const char* s) {
    return std::count_if(jobs.begin(), jobs.end(), [&](const Job& j) { return j.status == s; });
  };
  const long passed = count("pass"), mismatched = count("mismatch"), errors = count("error"), skips = count("skipped");
  std::cout << "\nregress: " << passed << " passed, " << mismatched << " mismatched, " << errors << " error(s), "
            << skips << " skipped (not in the build, or the scene does not fit it) in " << fmt(wall, 1) << " s with " << workers
            << " job(s); seed " << o.seed << '\n';

  if (!o.junit_path.empty()) {
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
    write_junit(o.junit_path, suite);
  }
  if (!o.json_path.empty()) {
    nlohmann::json all = nlohmann::json::array();
    for (const auto& j : jobs) {
      all.push_back({{"scene", j.scene}, {"config", j.config}, {"backend", j.backend}, {"status", j.status},
                     {"pixels", j.pixels}, {"cycles", j.cycles},
                     {"cycles_per_pixel", j.pixels ? static_cast<double>(j.cycles) / static_cast<double>(j.pixels) : 0.0},
                     {"seconds", j.seconds}, {"cycles_per_second", j.cycles_per_second}, {"seed", j.seed},
                     {"message", j.message}, {"replay", j.replay}, {"stream", j.stream_path}, {"log", j.log_path},
                     {"waves", j.waves_path}});
    }
    std::ofstream os(o.json_path);
    if (!os) throw std::runtime_error(o.json_path + ": cannot open for writing");
    os << nlohmann::json{{"seed", o.seed}, {"passed", passed}, {"mismatched", mismatched}, {"errors", errors},
                         {"skipped", skips}, {"wall_seconds", wall}, {"jobs", all}}
              .dump(2)
       << '\n';
  }
  return (mismatched > 0 || errors > 0) ? 1 : 0;
}

}  // namespace

void register_regress(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<RegressOptions>();
  CLI::App* sub = app.add_subcommand(
      "regress",
      "RTL regression, the main job: every scene x every Verilated configuration x both backends\n"
      "(Verilator C++ and Verilator-in-SystemC). Each run compares every pixel bit for bit with the\n"
      "bit-accurate model and every scanline's completion cycle with the cycle model, under seeded\n"
      "input gaps and output back-pressure. Exits 1 on any mismatch, naming it with a replay command.");
  sub->add_option("scenes", o->scenes, "scene files (default: scenes/*.json)")->check(CLI::ExistingFile);
  sub->add_option("--configs", o->configs, "configurations to run (default: all without injected faults; see --list)")
      ->delimiter(',')->allow_extra_args(false);
  sub->add_option("--backends", o->backends, "cpp, systemc or both (comma-separated)")
      ->delimiter(',')->allow_extra_args(false)->capture_default_str();
  sub->add_option("--seed", o->seed, "seed of the stimulus (printed on every run)")->capture_default_str();
  sub->add_option("-j,--jobs", o->jobs, "parallel co-simulations (default: hardware threads)")->check(CLI::NonNegativeNumber);
  sub->add_option("--gap-pct", o->gap_pct, "chance of idle cycles before a command word")->check(CLI::Range(0, 100))->capture_default_str();
  sub->add_option("--max-gap", o->max_gap, "longest idle gap in cycles")->check(CLI::Range(1, 100000))->capture_default_str();
  sub->add_option("--stall-pct", o->stall_pct, "chance of output back-pressure per cycle")->check(CLI::Range(0, 99))->capture_default_str();
  sub->add_option("-o,--out", o->out_dir, "where streams, results, logs and waveforms go")->capture_default_str();
  sub->add_option("--junit", o->junit_path, "write JUnit XML for CI");
  sub->add_option("--json", o->json_path, "write every run's figures as JSON");
  sub->add_option("--cosim-dir", o->cosim_dir, "directory holding rtl_cosim_cpp / rtl_cosim_sc (default: next to shadesim)");
  sub->add_flag("--waves", o->waves, "on a mismatch, re-run the C++ backend with FST tracing of the window around it");
  sub->add_flag("--list", o->list, "list the Verilated configurations and exit");
  sub->callback([o, &exit_code]() { exit_code = run_regress(*o); });
}

}  // namespace shadesim
