// RTL builds on demand: the co-simulation executable of one parameter set, Verilated and compiled
// into a cache folder the first time a run needs it and reused after that.
//
// The cache key is a hash of everything the executable is made from: shade_unit's parameters
// (model/rtl_parameters.h), the backend, the contents of the RTL, of the harness sources and
// headers, of the model headers and of the prebuilt model and harness libraries it links, the
// compiler's and Verilator's versions and the build flags. A changed input is a new key; an old
// entry is never rebuilt in place.
//
// Concurrency: a build holds an exclusive lock on <key>.lock (flock) while it works in a
// private temporary folder, which it renames into place when the executable is complete. A
// second process wanting the same key waits for the lock and then finds the finished build; if
// locks do not work (some network filesystems), the rename is still atomic and a loser discards
// its own copy. A failed build leaves its log in <cache>/failed/ and nothing under the key.
#pragma once

#include <string>
#include <vector>

#include "sim/harness/rtl_config.h"

namespace shadesim {

enum class CosimBackend { kCpp, kSystemC, kCppTrace };

std::string to_string(CosimBackend b);                 // cpp, systemc, cpp_trace
CosimBackend parse_cosim_backend(const std::string&);  // cpp | systemc (throws naming the value)

struct RtlBuildOptions {
  std::string cache_dir;  // empty: <build dir>/rtl-cache
  int make_jobs = 1;      // parallel compiler processes of one build
  bool quiet = false;     // no progress lines
  // Verilator line, toggle and user (cover property) coverage; the executable then takes
  // --coverage FILE.dat. Part of the key: covered and plain builds never share an entry.
  bool coverage = false;
};

struct RtlBuildResult {
  std::string executable;
  std::string key;
  bool built = false;  // false: found in the cache
  double seconds = 0;
};

// The default cache folder (under the build folder shadesim was built in).
std::string default_rtl_cache_dir();

// The cache key of a build (hex), without building it.
std::string rtl_build_key(const RtlConfig& build, CosimBackend backend, bool coverage = false);

// The executable for `build` on `backend`, building it first when the cache lacks it. Throws
// std::runtime_error naming the missing tool (verilator, make, the compiler) or the failed
// step with its log.
RtlBuildResult ensure_rtl_build(const RtlConfig& build, CosimBackend backend,
                                const RtlBuildOptions& options);

// shade_unit's RTL sources in dependency order, leaves first (SHADESIM_RTL_DIR: another copy).
std::vector<std::string> rtl_source_files();

// Where the project's sources are (the checkout shadesim was built from).
std::string source_dir();
// The user cover points bound into shade_unit in covered builds (sim/harness/shade_cover.sv).
std::string cover_points_file();
// The named builds file, sim/harness/builds.json.
std::string named_builds_path();

// A named build, or a UnitConfig JSON file (anything ending in .json); `what` names the option.
RtlConfig resolve_rtl_config(const std::string& name_or_file, const std::string& what);

}  // namespace shadesim
