// The engines of shadesim cosim / rtl-build / rtl-params (their options: sim/cli/cosim.cpp):
// co-simulation of any unit configuration, with the RTL Verilated on demand into the build cache
// (sim/eda/verilator/rtl_build.h).
#include "sim/engines/cosim.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>
#include <utility>
#include <variant>

#include "model/command_stream.h"
#include "sim/eda/verilator/replay.h"
#include "sim/eda/verilator/rtl_build.h"
#include "sim/eda/yosys/unit_netlist.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

// How hard to compile a build this run needs, when --opt does not say: a --stream by its length
// (4 cycles a pixel, regress's upper estimate), the random scenarios quick - they are short by
// design (every scenario of one seed is under 0.3 M cycles on grey_s428w, 0.1 s of simulation
// on a fast build and about 1 s on a quick one, which compiles about 5 s sooner).
RtlOptimization cosim_optimization(const std::string& optimization, const std::string& stream,
                                   bool coverage) {
  if (!optimization.empty()) return parse_rtl_optimization(optimization);
  if (stream.empty()) return RtlOptimization::kQuick;
  uint64_t pixels = 0;
  for (const Command& c : CommandStream::load(stream).commands) {
    if (const auto* s = std::get_if<SpanCmd>(&c)) pixels += static_cast<uint64_t>(s->length);
  }
  return choose_optimization(4 * pixels, coverage);
}

// The unit file the executable reads (--unit): content-addressed, written atomically.
std::string write_unit_file(const fs::path& cache, const UnitConfig& unit) {
  const std::string text = config_to_json(unit);
  const std::string name = "unit-" + std::to_string(std::hash<std::string>{}(text)) + ".json";
  const fs::path dir = cache / "units";
  fs::create_directories(dir);
  const fs::path path = dir / name;
  if (!fs::exists(path)) {
    const fs::path tmp = dir / (name + ".tmp." + std::to_string(getpid()));
    {
      std::ofstream os(tmp);
      os << text << '\n';
      if (!os) throw std::runtime_error("cosim: cannot write " + tmp.string());
    }
    fs::rename(tmp, path);
  }
  return path.string();
}

void list_named(bool json) {
  const std::vector<RtlConfig> builds = load_named_builds(named_builds_path());
  if (json) {
    nlohmann::json all = nlohmann::json::array();
    for (const auto& b : builds) {
      all.push_back({{"name", b.name},
                     {"unit", nlohmann::json::parse(config_to_json(b.unit))},
                     {"fault_hooks", b.faults.hooks},
                     {"backends", b.backends}});
    }
    std::cout << all.dump(2) << '\n';
    return;
  }
  for (const auto& b : builds) {
    std::string backends;
    for (const auto& s : b.backends) backends += (backends.empty() ? "" : ",") + s;
    std::cout << std::left << std::setw(18) << b.name << std::setw(13) << backends
              << b.unit.to_string() << fault_text(b.faults) << '\n';
  }
}

// Whether the co-simulation's own options inject a deliberate fault (--fault SITE@Y).
bool injects_fault(const std::vector<std::string>& passthrough) {
  return std::any_of(passthrough.begin(), passthrough.end(), [](const std::string& a) {
    return a == "--fault" || a.rfind("--fault=", 0) == 0;
  });
}

int exec_cosim(const CosimOptions& o) {
  if (o.list) {
    list_named(o.list_json);
    return 0;
  }
  CosimBackend backend = parse_cosim_backend(o.backend);
  RtlConfig build;
  if (!o.config.empty()) {
    build = build_for_run(resolve_rtl_config(o.config, "--config"), injects_fault(o.passthrough));
  } else if (!o.stream.empty()) {
    build.name = "stream";
    build.unit = CommandStream::load(o.stream).config;  // CommandStreamError names the file
  } else {
    throw std::invalid_argument(
        "cosim: name the unit with --config NAME|FILE.json (see --list), or "
        "replay a --stream, whose header names it");
  }
  if (!o.waves.empty()) {
    if (backend != CosimBackend::kCpp)
      throw std::invalid_argument("--waves: only the cpp backend traces");
    backend = CosimBackend::kCppTrace;
  }
  RtlBuildOptions bo;
  bo.cache_dir = o.cache;
  bo.make_jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  bo.coverage = !o.coverage.empty();
  bo.optimization = cosim_optimization(o.optimization, o.stream, bo.coverage);
  if (bo.coverage && backend == CosimBackend::kCppTrace) {
    throw std::invalid_argument(
        "--coverage and --waves: a traced build has no coverage; run them one at a time");
  }
  if (o.netlist) {
    if (bo.coverage) throw std::invalid_argument("--netlist: a gate-level netlist has no coverage");
    // A netlist has no fault hooks: they are simulation apparatus bound into the RTL.
    build.faults = InjectedFaults{};
    NetlistOptions no;
    no.cache_dir = o.netlist_cache.empty() ? default_netlist_cache_dir() : o.netlist_cache;
    no.progress = &std::cerr;
    const UnitNetlist n = unit_netlist(build.unit, no);
    build.netlist = n.path;
    std::cerr << "cosim: gate-level netlist " << n.path << " (" << n.cells << " cells, "
              << n.gate_equivalents << " GE" << (n.from_cache ? ", cached" : "") << ")"
              << std::endl;
  }
  const RtlBuildResult r = ensure_rtl_build(build, backend, bo);
  const fs::path cache(o.cache.empty() ? default_rtl_cache_dir() : o.cache);
  std::vector<std::string> args = {r.executable, "--unit", write_unit_file(cache, build.unit),
                                   "--config", build.name};
  args.insert(args.end(), {"--replay-prefix",
                           cosim_replay_prefix(o.backend, o.cache, o.netlist, o.netlist_cache)});
  if (!o.stream.empty()) args.insert(args.end(), {"--stream", o.stream});
  if (!o.waves.empty()) args.insert(args.end(), {"--waves", o.waves});
  if (!o.coverage.empty()) args.insert(args.end(), {"--coverage", o.coverage});
  args.insert(args.end(), o.passthrough.begin(), o.passthrough.end());
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::cout.flush();
  execv(argv[0], argv.data());
  throw std::runtime_error("cosim: cannot run " + r.executable + ": " + std::strerror(errno));
}

}  // namespace

int run_rtl_build(const RtlBuildCommandOptions& o) {
  if (o.print_source_dir) {
    std::cout << source_dir() << '\n';
    return 0;
  }
  if (o.print_rtl_sources) {
    for (const auto& p : rtl_source_files()) std::cout << p << '\n';
    return 0;
  }
  struct Item {
    RtlConfig config;
    CosimBackend backend;
    std::string result;
    bool failed = false;
  };
  std::vector<Item> items;
  std::vector<RtlConfig> configs;
  if (o.all) configs = load_named_builds(named_builds_path());
  for (const auto& c : o.configs) configs.push_back(resolve_rtl_config(c, "--config"));
  if (o.fault_hooks) {
    const auto no_hooks = [](const RtlConfig& c) { return !c.faults.hooks; };
    configs.erase(std::remove_if(configs.begin(), configs.end(), no_hooks), configs.end());
    if (configs.empty() && !o.runtime)
      throw std::invalid_argument("rtl-build --fault-hooks: none of these builds has fault hooks");
  } else {
    for (auto& c : configs) c = build_for_run(c, false);
  }
  const int workers =
      std::max(1, o.jobs > 0 ? o.jobs : static_cast<int>(std::thread::hardware_concurrency()));
  if (o.runtime) {
    // Every flavour's runtime, so that no first build of a configuration pays for one.
    RtlBuildOptions bo;
    bo.cache_dir = o.cache;
    bo.make_jobs = workers;
    for (const CosimBackend be :
         {CosimBackend::kCpp, CosimBackend::kSystemC, CosimBackend::kCppTrace}) {
      for (const bool covered : {false, true}) {
        // Coverage runs on the C++ backend (regress --coverage); a traced build has none.
        if (covered && be != CosimBackend::kCpp) continue;
        Flavour f;
        f.backend = be;
        f.coverage = covered;
        std::cout << std::left << std::setw(17) << "runtime" << ' ' << std::setw(9) << f.name()
                  << ' ' << ensure_rtl_runtime(f, bo) << '\n';
      }
    }
    if (configs.empty()) return 0;
  }
  if (configs.empty()) {
    throw std::invalid_argument("rtl-build: name builds with --config, or --all (or --runtime)");
  }
  for (const auto& c : configs) {
    // --backends given: those; otherwise each named build's own (cpp for a file).
    std::vector<std::string> names = o.backends;
    if (names.empty()) names = c.backends.empty() ? std::vector<std::string>{"cpp"} : c.backends;
    for (const auto& b : names) {
      const CosimBackend be = b == "cpp_trace" ? CosimBackend::kCppTrace : parse_cosim_backend(b);
      items.push_back({c, be, "", false});
    }
  }
  if (o.print_key) {
    for (const auto& it : items)
      std::cout << rtl_build_key(it.config, it.backend, o.coverage, o.cache,
                                 parse_rtl_optimization(o.optimization))
                << '\n';
    return 0;
  }
  // Fewer builds than workers: each build's compiler runs on the spare cores.
  const int per_build = std::max<int>(1, workers / static_cast<int>(items.size()));
  std::atomic<size_t> next{0};
  std::mutex m;
  size_t done = 0;
  auto work = [&]() {
    for (size_t i = next++; i < items.size(); i = next++) {
      RtlBuildOptions bo;
      bo.cache_dir = o.cache;
      bo.make_jobs = per_build;
      bo.coverage = o.coverage;
      bo.optimization = parse_rtl_optimization(o.optimization);
      try {
        const RtlBuildResult r = ensure_rtl_build(items[i].config, items[i].backend, bo);
        items[i].result = r.executable + (r.built ? "" : r.relinked ? " (relinked)" : " (cached)");
      } catch (const std::exception& e) {
        items[i].failed = true;
        items[i].result = e.what();
      }
      std::lock_guard<std::mutex> lock(m);
      std::cerr << "rtl build: [" << ++done << "/" << items.size() << "] " << items[i].config.name
                << " (" << to_string(items[i].backend) << ") "
                << (items[i].failed ? "FAILED" : "ready") << std::endl;
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(static_cast<size_t>(std::max(workers, 0)));
  for (int w = 0; w < workers; ++w) pool.emplace_back(work);
  for (auto& t : pool) t.join();
  int failed = 0;
  for (const auto& it : items) {
    std::cout << std::left << std::setw(17) << it.config.name << ' ' << std::setw(9)
              << to_string(it.backend) << ' ' << (it.failed ? "FAILED: " : "") << it.result << '\n';
    failed += it.failed ? 1 : 0;
  }
  return failed == 0 ? 0 : 1;
}

namespace {

// Failed before the co-simulation started: its --json file still says why.
void write_failure_json(const std::vector<std::string>& rest, const std::exception& e) {
  for (size_t i = 0; i + 1 < rest.size(); ++i) {
    if (rest[i] == "--json") {
      std::ofstream os(rest[i + 1]);
      if (os) os << nlohmann::json{{"passed", false}, {"error", e.what()}}.dump(2) << '\n';
    }
  }
}

}  // namespace

int run_cosim(const CosimOptions& o) {
  try {
    return exec_cosim(o);
  } catch (const std::exception& e) {
    write_failure_json(o.passthrough, e);
    throw;
  }
}

int run_rtl_params(const RtlParamsOptions& o) {
  const RtlConfig c = resolve_rtl_config(o.config, "--config");
  const auto list = shade_unit_parameters(c.unit);
  if (o.tool == "verilator") {
    for (const auto& a : verilator_parameter_args(list)) std::cout << a << '\n';
  } else if (o.tool == "iverilog") {
    // The testbench's own FAULT_HOOKS instantiates the hooks beside the unit (Icarus has no bind).
    std::vector<VerilogParameter> tb = list;
    if (c.faults.hooks) tb.push_back({"FAULT_HOOKS", 1});
    for (const auto& a : iverilog_parameter_args(tb, "tb_shade_unit")) std::cout << a << '\n';
  } else if (o.tool == "yosys") {
    std::cout << yosys_chparam_args(list) << '\n';
  } else {
    throw std::invalid_argument("--tool '" + o.tool + "': expected verilator, iverilog or yosys");
  }
  return 0;
}

}  // namespace shadesim
