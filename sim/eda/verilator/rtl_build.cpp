#include "sim/eda/verilator/rtl_build.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "model/rtl_parameters.h"
#include "model/unit_config_file.h"
#include "sim/eda/common/content_hash.h"
#include "sim/eda/common/rtl_files.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

// Bumped when the way a build is made changes in a way its inputs do not show, so old entries
// miss. 3: Verilated model, glue and link kept apart (sim/eda/verilator/rtl_recipe.h).
constexpr const char* kRecipeVersion = "rtl-build 3";

// shade_unit's sources in dependency order, leaves first (Icarus and Yosys want it too): the
// one list rtl/files.f, which CMake (cmake/rtl_files.cmake) and `shadesim area` read too.
std::vector<fs::path> rtl_sources() {
  // SHADESIM_RTL_DIR: another copy of rtl/ (mutation testing, the cache test).
  const char* other = std::getenv("SHADESIM_RTL_DIR");
  const fs::path rtl = other && *other ? fs::path(other) : fs::path(source_dir()) / "rtl";
  return rtl_file_list(rtl.string());
}

// The harness's deliberate-fault hooks (test apparatus, outside rtl/): their list, then the bind
// that puts them into shade_unit.
std::vector<fs::path> fault_hook_sources() {
  const fs::path dir = fs::path(source_dir()) / "sim" / "harness" / "faults";
  std::vector<fs::path> out = rtl_file_list(dir.string());
  out.push_back(dir / "fault_bind.sv");
  return out;
}

// What a simulation of `build` compiles: the RTL, then, in a build with fault hooks, the hooks.
std::vector<fs::path> simulation_sources(const RtlConfig& build) {
  std::vector<fs::path> out = rtl_sources();
  if (build.faults.hooks) {
    const std::vector<fs::path> hooks = fault_hook_sources();
    out.insert(out.end(), hooks.begin(), hooks.end());
  }
  return out;
}

// The contents of `files`, each with its name, into `h`; a missing one is an error naming it.
void add_files(ContentHash& h, const std::vector<fs::path>& files) {
  for (const auto& p : files) {
    if (!fs::exists(p)) {
      throw std::runtime_error("rtl build: " + p.string() +
                               " is missing; build the project first (scripts/build)");
    }
    h.add(p.filename().string());
    h.add(read_text(p));
  }
}

fs::path cache_of(const std::string& dir) {
  // Absolute: the compiler runs in the build's own folders.
  return fs::absolute(dir.empty() ? default_rtl_cache_dir() : dir);
}

// The tools, found once per process and cache folder.
const Toolchain& toolchain(const fs::path& cache) {
  static std::mutex m;
  static std::map<std::string, Toolchain> known;
  std::lock_guard<std::mutex> lock(m);
  auto it = known.find(cache.string());
  if (it == known.end()) it = known.emplace(cache.string(), find_toolchain(cache)).first;
  return it->second;
}

Flavour flavour_of(CosimBackend backend, bool coverage) {
  Flavour f;
  f.backend = backend;
  f.coverage = coverage;
  return f;
}

std::string runtime_key(const Flavour& f, const Toolchain& t) {
  ContentHash h;
  h.add(kRecipeVersion).add("runtime").add(recipe_text(f, t));
  return h.hex();
}

// The RTL's contents, read once per process (the same for every build of it).
std::string digest_of(const std::vector<fs::path>& files) {
  ContentHash h;
  add_files(h, files);
  return h.hex();
}
const std::string& rtl_digest() {
  static const std::string digest = digest_of(rtl_sources());
  return digest;
}
const std::string& fault_hooks_digest() {
  static const std::string digest = digest_of(fault_hook_sources());
  return digest;
}

// `assertions`: Verilated with the RTL's SVA (checks_assertions); the same build without them
// is another model.
std::string model_key(const RtlConfig& build, const Flavour& f, const Toolchain& t,
                      bool assertions = true) {
  ContentHash h;
  h.add(kRecipeVersion).add("model").add(recipe_text(f, t));
  if (assertions) h.add("verilator --assert");
  if (build.netlist.empty()) {
    h.add(rtl_digest());
    if (build.faults.hooks) h.add("fault hooks").add(fault_hooks_digest());
  } else {
    // A gate-level netlist: its own contents are the circuit (an edited netlist is a new build).
    if (f.coverage)
      throw std::invalid_argument("rtl build: a netlist build has no coverage (" + build.name +
                                  ")");
    if (!fault_text(build.faults).empty())
      throw std::invalid_argument("rtl build: a netlist build has no fault hooks (" + build.name +
                                  ")");
    h.add("netlist");
    for (const auto& o : netlist_verilator_options()) h.add(o);
    add_files(h, {fs::path(build.netlist)});
  }
  for (const auto& p : shade_unit_parameters(build.unit)) h.add(p.name + "=" + p.literal());
  if (f.coverage) {
    h.add("coverage: line toggle user");
    add_files(h, {cover_points_file()});
    // Verilator writes the sources' paths into coverage.dat and regress --coverage matches them
    // against its own checkout's rtl/: a covered build of another checkout's (identical) sources
    // is not this one's.
    for (const auto& p : simulation_sources(build)) h.add(fs::absolute(p).string());
    h.add(fs::absolute(cover_points_file()).string());
  }
  return h.hex();
}

// The glue's and the libraries' contents, once per process.
const std::string& glue_digest() {
  static const std::string digest = digest_of(glue_sources());
  return digest;
}
const std::string& libraries_digest() {
  static const std::string digest = digest_of(harness_libraries());
  return digest;
}

// Holds an exclusive flock on a file for its lifetime.
class FileLock {
 public:
  explicit FileLock(const fs::path& path) : fd_(open(path.c_str(), O_RDWR | O_CREAT, 0644)) {
    if (fd_ < 0) throw std::runtime_error("rtl build: cannot create lock " + path.string());
    while (flock(fd_, LOCK_EX) != 0) {
      if (errno != EINTR) break;  // no locking here: the atomic renames still keep the cache whole
    }
  }
  ~FileLock() { close(fd_); }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  int fd_;
};

bool try_lock_now(const fs::path& path) {
  const int fd = open(path.c_str(), O_RDWR | O_CREAT, 0644);
  if (fd < 0) return true;
  const bool free = flock(fd, LOCK_EX | LOCK_NB) == 0;
  close(fd);
  return free;
}

// Host and pid: on a cache shared over NFS two hosts can have the same pid.
std::string private_suffix() {
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  return std::string(".tmp.") + host + "." + std::to_string(getpid());
}

// Runs `make` (which writes into the temporary path it is given), then renames the result into
// `final_path`; on failure keeps the log in <cache>/failed/ and throws.
template <class Make>
void make_atomically(const fs::path& final_path, const fs::path& cache, const fs::path& log,
                     Make make) {
  const fs::path tmp = final_path.string() + private_suffix();
  std::error_code ec;
  fs::remove_all(tmp, ec);
  try {
    make(tmp);
  } catch (...) {
    fs::create_directories(cache / "failed", ec);
    fs::copy_file(log, cache / "failed" / (final_path.filename().string() + ".log"),
                  fs::copy_options::overwrite_existing, ec);
    fs::remove_all(tmp, ec);
    throw;
  }
  fs::rename(tmp, final_path, ec);
  if (ec) {
    fs::remove_all(tmp, ec);
    if (!fs::exists(final_path))
      throw std::runtime_error("rtl build: cannot move " + tmp.string() + " into place");
  }
}

fs::path runtime_dir(const fs::path& cache, const Flavour& f, const Toolchain& t) {
  return cache / "runtime" / (f.name() + "-" + runtime_key(f, t));
}

fs::path ensure_runtime(const fs::path& cache, const Flavour& f, const Toolchain& t, int jobs,
                        bool quiet) {
  fs::path dir = runtime_dir(cache, f, t);  // returned: moved
  if (fs::exists(dir)) return dir;
  fs::create_directories(dir.parent_path());
  FileLock lock(dir.string() + ".lock");
  if (fs::exists(dir)) return dir;
  if (!quiet)
    std::cerr << "rtl build: compiling the Verilator runtime for " << f.name() << " builds into "
              << dir.string() << " (once per flavour)..." << std::endl;
  const fs::path log = dir.string() + ".log";
  make_atomically(dir, cache, log, [&](const fs::path& tmp) {
    fs::create_directories(tmp);
    build_runtime(tmp, f, t, jobs, log);
  });
  return dir;
}

// Executable and its parts for one optimisation inside a build folder.
struct Products {
  fs::path objects, glue, exe;
};
Products products(const fs::path& dir, RtlOptimization opt, const std::string& runtime) {
  const std::string o = to_string(opt);
  const std::string glue_key = glue_digest().substr(0, 16);
  ContentHash link;
  link.add(kRecipeVersion).add(glue_key).add(runtime).add(libraries_digest());
  return {dir / ("model-" + o), dir / ("glue-" + o + "-" + glue_key + ".o"),
          dir / ("cosim-" + o + "-" + link.hex().substr(0, 16))};
}

// Older executables of the same optimisation (their libraries changed since): not used again.
void remove_stale_executables(const fs::path& dir, const fs::path& keep, RtlOptimization opt) {
  const std::string prefix = "cosim-" + to_string(opt) + "-";
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) == 0 && e.path() != keep) fs::remove(e.path(), ec);
  }
}

// The Verilated model of `build` in `dir` (the caller holds the build's lock); true when this
// call Verilated it.
bool ensure_verilated(const fs::path& dir, const fs::path& cache, const RtlConfig& build,
                      const Flavour& flavour, bool assertions, const Toolchain& tools, bool quiet) {
  if (fs::exists(dir)) return false;
  const fs::path log = dir.string() + ".log";
  if (!quiet) {
    std::cerr << "rtl build: Verilating " << build.name
              << (build.netlist.empty() ? "" : " (gate-level netlist " + build.netlist + ")")
              << " [" << build.unit.to_string() << fault_text(build.faults) << "] for the "
              << flavour.name() << " backend" << (assertions ? "" : " without its SVA") << " into "
              << dir.string() << std::endl;
  }
  std::ofstream(log, std::ios::trunc).flush();
  make_atomically(dir, cache, log, [&](const fs::path& tmp) {
    fs::create_directories(tmp);
    std::vector<std::string> sources;
    for (const auto& p : simulation_sources(build)) sources.push_back(p.string());
    verilate(tmp, build, flavour, assertions, tools, sources, cover_points_file(), log);
  });
  return true;
}

}  // namespace

std::vector<std::string> rtl_source_files() {
  std::vector<std::string> out;
  for (const auto& p : rtl_sources()) out.push_back(p.string());
  return out;
}

std::string cover_points_file() {
  return (fs::path(source_dir()) / "sim" / "harness" / "shade_cover.sv").string();
}

std::string named_builds_path() {
  return (fs::path(source_dir()) / "sim" / "harness" / "builds.json").string();
}

std::string default_rtl_cache_dir() { return (fs::path(binary_dir()) / "rtl-cache").string(); }

std::string rtl_build_key(const RtlConfig& build, CosimBackend backend, bool coverage,
                          const std::string& cache_dir, RtlOptimization optimization) {
  const fs::path cache = cache_of(cache_dir);
  const Flavour f = flavour_of(backend, coverage);
  return model_key(build, f, toolchain(cache), checks_assertions(f, optimization));
}

RtlConfig resolve_rtl_config(const std::string& name_or_file, const std::string& what) {
  try {
    if (fs::path(name_or_file).extension() == ".json") {
      RtlConfig c;
      c.name = name_or_file;
      try {
        c.unit = load_unit_config(name_or_file);
      } catch (const UnitConfigFileError& e) {
        throw std::invalid_argument(e.what());
      }
      c.backends = {"cpp", "systemc"};
      return c;
    }
    return named_build(named_builds_path(), name_or_file);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(what + ": " + e.what());
  }
}

std::string ensure_rtl_runtime(const Flavour& flavour, const RtlBuildOptions& o) {
  const fs::path cache = cache_of(o.cache_dir);
  return ensure_runtime(cache, flavour, toolchain(cache), o.make_jobs, o.quiet).string();
}

RtlBuildResult ensure_rtl_build(const RtlConfig& build, CosimBackend backend,
                                const RtlBuildOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path cache = cache_of(o.cache_dir);
  const Toolchain& tools = toolchain(cache);
  const Flavour flavour = flavour_of(backend, o.coverage);
  const std::string rkey = runtime_key(flavour, tools);
  RtlBuildResult r;
  const bool assertions = checks_assertions(flavour, o.optimization);
  r.key = model_key(build, flavour, tools, assertions);
  const fs::path dir = cache / (flavour.name() + "-" + r.key);
  // A fast executable of the same model serves a quick request too (a covered build's: both
  // check the SVA).
  for (const auto opt : {RtlOptimization::kFast, o.optimization}) {
    if (checks_assertions(flavour, opt) != assertions) continue;
    const Products p = products(dir, opt, rkey);
    if (fs::exists(p.exe)) {
      r.executable = p.exe.string();
      r.optimization = opt;
      return r;
    }
  }
  const fs::path runtime = ensure_runtime(cache, flavour, tools, o.make_jobs, o.quiet);
  fs::create_directories(cache);
  const fs::path lock_path = dir.string() + ".lock";
  if (!o.quiet && !try_lock_now(lock_path)) {
    std::cerr << "rtl build: waiting for another process or thread building " << build.name << " ("
              << flavour.name() << ", key " << r.key.substr(0, 12) << ")" << std::endl;
  }
  FileLock lock(lock_path);
  const Products p = products(dir, o.optimization, rkey);
  r.executable = p.exe.string();
  r.optimization = o.optimization;
  if (fs::exists(p.exe)) return r;  // made by the process we waited for

  const std::string what = build.name + " [" + build.unit.to_string() + fault_text(build.faults) +
                           "] for the " + flavour.name() + " backend";
  const fs::path log = dir.string() + ".log";
  r.built = ensure_verilated(dir, cache, build, flavour, assertions, tools, o.quiet);
  // The glue compiles beside the model's objects (it is on no one's critical path then).
  std::exception_ptr glue_error;
  const bool glue_needed = !fs::exists(p.glue);
  std::thread glue([&] {
    try {
      if (!fs::exists(p.glue)) {
        make_atomically(p.glue, cache, log, [&](const fs::path& tmp) {
          compile_glue(dir, tmp, flavour, tools, runtime, o.optimization, log);
        });
      }
    } catch (...) {
      glue_error = std::current_exception();
    }
  });
  struct Joiner {  // on an exception from the model's compile
    std::thread& t;
    ~Joiner() {
      if (t.joinable()) t.join();
    }
  } joiner{glue};
  std::vector<fs::path> objects;
  if (!fs::exists(p.objects)) {
    if (!o.quiet && !r.built)
      std::cerr << "rtl build: compiling " << what << " (" << to_string(o.optimization) << ")"
                << std::endl;
    make_atomically(p.objects, cache, log, [&](const fs::path& tmp) {
      // One core is the glue's while it compiles.
      const int jobs = std::max(1, o.make_jobs - (glue_needed ? 1 : 0));
      compile_model(dir, tmp, flavour, tools, runtime, o.optimization, jobs, log);
    });
    r.built = true;
  }
  for (const auto& e : fs::directory_iterator(p.objects))
    if (e.path().extension() == ".o") objects.push_back(e.path());
  std::sort(objects.begin(), objects.end());
  if (!r.built && !o.quiet)
    std::cerr << "rtl build: relinking " << what << " (the model or harness libraries changed; "
              << "its Verilated objects are reused)" << std::endl;
  glue.join();
  if (glue_error) std::rethrow_exception(glue_error);
  make_atomically(p.exe, cache, log, [&](const fs::path& tmp) {
    link_executable(tmp, objects, p.glue, flavour, tools, runtime, log);
  });
  remove_stale_executables(dir, p.exe, o.optimization);
  r.relinked = !r.built;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!o.quiet) {
    std::cerr << "rtl build: " << build.name << " (" << flavour.name() << ", "
              << to_string(o.optimization) << ") " << (r.built ? "built" : "relinked") << " in "
              << std::fixed << std::setprecision(1) << r.seconds << " s" << std::defaultfloat
              << std::endl;
  }
  return r;
}

RtlPrefetch::RtlPrefetch(const RtlBuildOptions& options, int workers)
    : options_(options), workers_(std::max(1, workers)) {}

RtlPrefetch::~RtlPrefetch() {
  {
    std::lock_guard<std::mutex> lock(m_);
    closed_ = true;
  }
  ready_.notify_all();
  for (auto& t : threads_) t.join();
}

void RtlPrefetch::add(const RtlConfig& build, CosimBackend backend, RtlOptimization optimization) {
  const Flavour flavour = flavour_of(backend, options_.coverage);
  const bool assertions = checks_assertions(flavour, optimization);
  const fs::path cache = cache_of(options_.cache_dir);
  std::string key;
  try {
    key = model_key(build, flavour, toolchain(cache), assertions);
  } catch (const std::exception&) {
    return;  // ensure_rtl_build reports it
  }
  std::lock_guard<std::mutex> lock(m_);
  if (!keys_.insert(key).second) return;
  queue_.push_back({build, flavour, assertions, cache / (flavour.name() + "-" + key)});
  if (threads_.size() < static_cast<size_t>(workers_)) threads_.emplace_back([this] { work(); });
  ready_.notify_one();
}

void RtlPrefetch::work() {
  for (;;) {
    Item item;
    {
      std::unique_lock<std::mutex> lock(m_);
      ready_.wait(lock, [this] { return closed_ || !queue_.empty(); });
      if (queue_.empty()) return;
      item = queue_.front();
      queue_.erase(queue_.begin());
    }
    try {
      const fs::path cache = cache_of(options_.cache_dir);
      fs::create_directories(cache);
      FileLock lock(item.dir.string() + ".lock");
      ensure_verilated(item.dir, cache, item.build, item.flavour, item.assertions, toolchain(cache),
                       options_.quiet);
    } catch (const std::exception&) {
      // ensure_rtl_build tries again and reports the error with its run.
    }
  }
}

}  // namespace shadesim
