// shadesim cosim / rtl-build / rtl-params: co-simulation of any unit configuration, with the RTL
// Verilated on demand into the build cache (sim/eda/rtl_build.h).
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>
#include <utility>
#include <variant>

#include "model/command_stream.h"
#include "sim/cli/commands.h"
#include "sim/cli/number_checks.h"
#include "sim/cli/output_paths.h"
#include "sim/eda/area.h"
#include "sim/eda/replay.h"
#include "sim/eda/rtl_build.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

struct CosimOptions {
  std::string backend = "cpp";
  std::string config;  // a named build or a UnitConfig FILE.json
  std::string stream;
  std::string waves;
  std::string cache;
  std::string coverage;       // FILE.dat: run the covered build, write its coverage there
  std::string optimization;   // quick | fast; empty: by the run's length (cosim_optimization)
  bool netlist = false;       // Yosys's gate-level netlist in place of the RTL
  std::string netlist_cache;  // empty: <build>/netlist-cache
  bool list = false;
  bool list_json = false;
};

// How hard to compile a build this run needs, when --opt does not say: a --stream by its length
// (4 cycles a pixel, regress's upper estimate), the random scenarios quick - they are short by
// design (every scenario of one seed is under 0.3 M cycles on grey_s428w, 0.1 s of simulation
// on a fast build and about 1 s on a quick one, which compiles about 5 s sooner).
RtlOptimization cosim_optimization(const std::string& optimization, const std::string& stream) {
  if (!optimization.empty()) return parse_rtl_optimization(optimization);
  if (stream.empty()) return RtlOptimization::kQuick;
  uint64_t pixels = 0;
  for (const Command& c : CommandStream::load(stream).commands) {
    if (const auto* s = std::get_if<SpanCmd>(&c)) pixels += static_cast<uint64_t>(s->length);
  }
  return choose_optimization(4 * pixels);
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

int run_cosim(const CosimOptions& o, std::vector<std::string> passthrough) {
  if (o.list) {
    list_named(o.list_json);
    return 0;
  }
  CosimBackend backend = parse_cosim_backend(o.backend);
  RtlConfig build;
  if (!o.config.empty()) {
    build = resolve_rtl_config(o.config, "--config");
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
  bo.optimization = cosim_optimization(o.optimization, o.stream);
  if (bo.coverage && backend == CosimBackend::kCppTrace) {
    throw std::invalid_argument(
        "--coverage and --waves: a traced build has no coverage; run them one at a time");
  }
  if (o.netlist) {
    if (bo.coverage) throw std::invalid_argument("--netlist: a gate-level netlist has no coverage");
    // The netlist is synthesised with FAULT_HOOKS 0: a fault-hook build's netlist has none.
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
  args.insert(args.end(), passthrough.begin(), passthrough.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::cout.flush();
  execv(argv[0], argv.data());
  throw std::runtime_error("cosim: cannot run " + r.executable + ": " + std::strerror(errno));
}

struct RtlBuildCliOptions {
  std::vector<std::string> configs;
  bool all = false;
  bool runtime = false;
  std::string optimization = "fast";
  std::vector<std::string> backends;
  std::string cache;
  int jobs = 0;
  bool print_key = false;
  bool coverage = false;
  bool print_source_dir = false;
  bool print_rtl_sources = false;
};

int run_rtl_build(const RtlBuildCliOptions& o) {
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
      std::cout << rtl_build_key(it.config, it.backend, o.coverage, o.cache) << '\n';
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

// The co-simulation's own outputs (forwarded options) are checked before any build starts.
void check_forwarded_outputs(const std::vector<std::string>& rest) {
  for (size_t i = 0; i < rest.size(); ++i) {
    for (const auto& [option, folder] : {std::pair<std::string, bool>{"--json", false},
                                         std::pair<std::string, bool>{"--save-dir", true}}) {
      if (rest[i] == option && i + 1 < rest.size()) {
        check_output_path(rest[i + 1], folder, option);
      } else if (rest[i].rfind(option + "=", 0) == 0) {
        check_output_path(rest[i].substr(option.size() + 1), folder, option);
      }
    }
  }
}

// Failed before the co-simulation started: its --json file still says why.
void write_failure_json(const std::vector<std::string>& rest, const std::exception& e) {
  for (size_t i = 0; i + 1 < rest.size(); ++i) {
    if (rest[i] == "--json") {
      std::ofstream os(rest[i + 1]);
      if (os) os << nlohmann::json{{"passed", false}, {"error", e.what()}}.dump(2) << '\n';
    }
  }
}

void register_cosim_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<CosimOptions>();
  CLI::App* sub = app.add_subcommand(
      "cosim",
      "Co-simulate one unit configuration: the Verilated RTL against the bit-accurate model "
      "(every\n"
      "pixel) and the cycle model (every scanline's cycle). The RTL is Verilated on demand into "
      "the\n"
      "build cache the first time a configuration is needed, and reused after that. Options not\n"
      "listed here go to the co-simulation itself: --scenario mixed|long|short|slow|maxbp|switch|\n"
      "tiny|edge|all, --seed, --runs, --gap-pct, --max-gap, --stall-pct, --expect-mismatch "
      "KIND:Y,\n"
      "--fault SITE@Y (a build with fault hooks: inject one deliberate fault),\n"
      "--save-dir, --json FILE, --min-spec-pct, --rows (run with any unit and --help to see "
      "them).");
  sub->add_option("--backend", o->backend, "cpp (Verilator C++) or systemc (Verilator in SystemC)")
      ->capture_default_str();
  sub->add_option("--config", o->config, "a named build (see --list) or a UnitConfig FILE.json");
  sub->add_option("--stream", o->stream,
                  "replay a saved command stream (text form; its header names the unit)");
  sub->add_option("--waves", o->waves,
                  "on a mismatch, write an FST of the cycles around it (cpp backend)")
      ->check(output_file());
  sub->add_option("--cache", o->cache, "build cache folder (default: <build>/rtl-cache)");
  sub->add_option(
         "--coverage", o->coverage,
         "run the covered build (line, toggle, user cover points) and write its Verilator\n"
         "coverage to FILE.dat, pass or fail (several runs: FILE_<i>.dat)")
      ->check(output_file());
  sub->add_option("--opt", o->optimization,
                  "compile a new build quick (-O0: builds fastest) or fast (-O2: simulates "
                  "fastest); a cached fast build is used either way. Default: quick for the "
                  "random scenarios (short), by the stream's length for --stream (quick under " +
                      std::to_string(kQuickBuildCycles) + " cycles)")
      ->check(CLI::IsMember({"quick", "fast"}));
  sub->add_flag("--netlist", o->netlist,
                "simulate the unit's gate-level netlist from Yosys (what `shadesim area` "
                "measures) in place of the RTL; no fault hooks, no coverage");
  sub->add_option("--netlist-cache", o->netlist_cache,
                  "with --netlist: folder of the cached netlists (default: <build>/netlist-cache)");
  sub->add_flag("--list", o->list, "list the named builds (sim/harness/builds.json)");
  sub->add_flag("--list-json", o->list_json, "with --list: as JSON");
  sub->allow_extras();
  sub->callback([o, sub, &exit_code]() {
    const std::vector<std::string> rest = sub->remaining();
    check_forwarded_outputs(rest);
    try {
      exit_code = run_cosim(*o, rest);
    } catch (const std::exception& e) {
      write_failure_json(rest, e);
      throw;
    }
  });
}

void register_rtl_build(CLI::App& app, int& exit_code) {
  auto b = std::make_shared<RtlBuildCliOptions>();
  CLI::App* build = app.add_subcommand(
      "rtl-build",
      "Verilate and compile co-simulation executables into the build cache ahead of time (the\n"
      "commands that need one build it on demand anyway). Prints each executable's path.");
  build->add_option("--config", b->configs, "named builds or UnitConfig FILE.json files")
      ->delimiter(',');
  build->add_flag("--all", b->all,
                  "every named build in sim/harness/builds.json, on its own backends");
  build
      ->add_option("--backends", b->backends, "cpp, systemc, cpp_trace (default: each build's own)")
      ->delimiter(',');
  build->add_option("--cache", b->cache, "build cache folder (default: <build>/rtl-cache)");
  build->add_option("-j,--jobs", b->jobs, "builds at once (default: hardware threads)")
      ->check(non_negative_number());
  build->add_flag("--coverage", b->coverage, "the covered builds (what regress --coverage runs)");
  build->add_flag("--runtime", b->runtime,
                  "compile the Verilator runtime of every flavour into the cache (once; the first "
                  "build of a new configuration then compiles only its own model)");
  build
      ->add_option("--opt", b->optimization,
                   "quick (-O0: builds fastest) or fast (-O2: simulates fastest)")
      ->capture_default_str()
      ->check(CLI::IsMember({"quick", "fast"}));
  build->add_flag("--print-key", b->print_key, "print each build's cache key and build nothing");
  build->add_flag("--print-source-dir", b->print_source_dir, "print the checkout the builds read");
  build->add_flag("--print-rtl-sources", b->print_rtl_sources,
                  "print shade_unit's sources, leaves first");
  build->callback([b, &exit_code]() { exit_code = run_rtl_build(*b); });
}

void register_rtl_params(CLI::App& app, int& exit_code) {
  auto p = std::make_shared<std::pair<std::string, std::string>>("", "verilator");
  CLI::App* params = app.add_subcommand(
      "rtl-params",
      "Print shade_unit's Verilog parameters for a configuration (model/rtl_parameters.h, the one\n"
      "mapping), one argument per line: verilator (-GNAME=V), iverilog (-Ptb_shade_unit.NAME=V)\n"
      "or yosys (chparam's -set NAME V list).");
  params->add_option("--config", p->first, "a named build or a UnitConfig FILE.json")->required();
  params->add_option("--tool", p->second, "verilator, iverilog or yosys")->capture_default_str();
  params->callback([p, &exit_code]() {
    const RtlConfig c = resolve_rtl_config(p->first, "--config");
    const auto list = shade_unit_parameters(c.unit, c.faults);
    if (p->second == "verilator") {
      for (const auto& a : verilator_parameter_args(list)) std::cout << a << '\n';
    } else if (p->second == "iverilog") {
      for (const auto& a : iverilog_parameter_args(list, "tb_shade_unit")) std::cout << a << '\n';
    } else if (p->second == "yosys") {
      std::cout << yosys_chparam_args(list) << '\n';
    } else {
      throw std::invalid_argument("--tool '" + p->second +
                                  "': expected verilator, iverilog or yosys");
    }
    exit_code = 0;
  });
}

}  // namespace

void register_cosim(CLI::App& app, int& exit_code) {
  register_cosim_command(app, exit_code);
  register_rtl_build(app, exit_code);
  register_rtl_params(app, exit_code);
}

}  // namespace shadesim
