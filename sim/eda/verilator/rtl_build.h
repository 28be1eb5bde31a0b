// RTL builds on demand: the co-simulation executable of one parameter set, Verilated and compiled
// into a cache folder the first time a run needs it and reused after that. How each part is
// made is sim/eda/verilator/rtl_recipe.h; what is kept under which key is this file:
//
//   <cache>/runtime/<flavour>-<key>/     Verilator's runtime and precompiled headers; key: the
//                                        flavour, the compiler, Verilator
//   <cache>/<flavour>-<key>/             the Verilated model; key (the build key): the RTL's
//                                        contents, shade_unit's parameters, the flavour, the
//                                        compiler, Verilator - nothing of the model or harness
//     model-<opt>/                       its objects, per optimisation (quick, fast)
//     glue-<opt>-<key>.o                 the glue; key: its sources
//     cosim-<opt>-<key>                  the executable; key: the glue, the runtime and the
//                                        contents of the harness and model libraries it links
// So a change to the model or the harness relinks every cached build (about 0.1 s each) and
// Verilates none; a change to the RTL or a parameter Verilates that build again.
//
// Concurrency: work on a build holds an exclusive lock on <flavour>-<key>.lock (flock); a
// Verilation happens in a private temporary folder renamed into place when complete, objects and
// executables are written under temporary names and renamed. A second process wanting the same
// build waits for the lock and then finds it. A failed build leaves its log in <cache>/failed/.
#pragma once

#include <condition_variable>
#include <filesystem>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "sim/eda/common/build_paths.h"
#include "sim/eda/verilator/rtl_recipe.h"
#include "sim/harness/rtl_config.h"

namespace shadesim {

struct RtlBuildOptions {
  std::string cache_dir;  // empty: <build dir>/rtl-cache
  int make_jobs = 1;      // parallel compiler processes of one build
  bool quiet = false;     // no progress lines
  // kQuick: -O0, for runs too short to repay -O2's compile time (choose_optimization). A fast
  // build of the same model (a covered one: checks_assertions) already in the cache serves either.
  RtlOptimization optimization = RtlOptimization::kFast;
  // Verilator line, toggle and user (cover property) coverage; the executable then takes
  // --coverage FILE.dat. Part of the key: covered and plain builds never share an entry.
  bool coverage = false;
};

struct RtlBuildResult {
  std::string executable;
  std::string key;
  bool built = false;     // Verilated (or compiled for another optimisation) by this call
  bool relinked = false;  // linked by this call from cached Verilated objects
  RtlOptimization optimization = RtlOptimization::kFast;  // of the executable returned
  double seconds = 0;
};

// Simulated cycles below which a quick (-O0) build finishes a run sooner than a fast (-O2) one:
// it compiles faster and simulates slower. `scripts/bench-new-config --opt quick` and `--opt
// fast` print both builds' times and simulation speeds; on sphere's own unit the fast build
// took about 1 s longer and simulated about 10x faster (0.2 against 2 M cycles/s and more), a
// crossover near 250 k cycles, and larger units take longer to optimise.
// A covered build counts every toggle every cycle, and at -O0 that code is 15x slower than a
// fast covered build's -O1 (schlick_iter_n_p4_l4_m2_mul covered, multi's 302,575-cycle stream:
// 152.2 s against 10.2 s), which took 12 s more to compile (its per-cycle half: 32 s against
// 20 s): a crossover near 26 k cycles on that unit. The shipped scenes' own units compile
// quick in 4-13 s and their runs are 20-110 k cycles, so the threshold sits above them.
constexpr uint64_t kQuickBuildCycles = 500000;
constexpr uint64_t kQuickCoveredBuildCycles = 100000;
inline RtlOptimization choose_optimization(uint64_t expected_cycles, bool coverage = false) {
  const uint64_t quick_below = coverage ? kQuickCoveredBuildCycles : kQuickBuildCycles;
  return expected_cycles < quick_below ? RtlOptimization::kQuick : RtlOptimization::kFast;
}

// The default cache folder (under the build folder shadesim was built in).
std::string default_rtl_cache_dir();

// The build key (hex) of a build: what its Verilated model is made from, without building it
// (the optimisation says whether the model checks the SVA: checks_assertions).
std::string rtl_build_key(const RtlConfig& build, CosimBackend backend, bool coverage = false,
                          const std::string& cache_dir = "",
                          RtlOptimization optimization = RtlOptimization::kQuick);

// The executable for `build` on `backend`, building it first when the cache lacks it. Throws
// std::runtime_error naming the missing tool (verilator, the compiler) or the failed step with
// its log.
RtlBuildResult ensure_rtl_build(const RtlConfig& build, CosimBackend backend,
                                const RtlBuildOptions& options);

// shade_unit's RTL sources in dependency order, leaves first (SHADESIM_RTL_DIR: another copy).
std::vector<std::string> rtl_source_files();

// Verilates builds in the background while the caller does other work (regress's host setup):
// add() queues a build; at most `workers` Verilator processes run at once; the destructor waits
// for them. ensure_rtl_build then finds the Verilated model (or waits on its lock) and only
// compiles and links. A failure here is silent: ensure_rtl_build tries again and reports it.
class RtlPrefetch {
 public:
  RtlPrefetch(const RtlBuildOptions& options, int workers);
  ~RtlPrefetch();
  RtlPrefetch(const RtlPrefetch&) = delete;
  RtlPrefetch& operator=(const RtlPrefetch&) = delete;
  // `optimization`: the one the build will be asked for (whether its model checks the SVA).
  void add(const RtlConfig& build, CosimBackend backend, RtlOptimization optimization);

 private:
  struct Item {
    RtlConfig build;
    Flavour flavour;
    bool assertions = true;
    std::filesystem::path dir;
  };
  void work();
  RtlBuildOptions options_;
  int workers_;
  std::mutex m_;
  std::condition_variable ready_;
  bool closed_ = false;
  std::set<std::string> keys_;
  std::vector<Item> queue_;
  std::vector<std::thread> threads_;
};

// Builds the runtime of a flavour into the cache now (the rtl_runtime target: so that the first
// build of a new configuration does not pay for it). Returns its folder.
std::string ensure_rtl_runtime(const Flavour& flavour, const RtlBuildOptions& options);

// The user cover points bound into shade_unit in covered builds (sim/harness/shade_cover.sv).
std::string cover_points_file();
// The named builds file, sim/harness/builds.json.
std::string named_builds_path();

// A named build, or a UnitConfig JSON file (anything ending in .json); `what` names the option.
RtlConfig resolve_rtl_config(const std::string& name_or_file, const std::string& what);

}  // namespace shadesim
