#include "sim/rtl_build.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "model/unit_config_file.h"
#include "sim/process.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

// Bumped when the way a build is made changes (flags, generated header), so old entries miss.
constexpr const char* kRecipeVersion = "rtl-build 2";  // 2: the driver in libshadesim_harness

std::string read_file(const fs::path& p) {
  std::ifstream is(p, std::ios::binary);
  std::stringstream ss;
  ss << is.rdbuf();
  return ss.str();
}

// FNV-1a, twice with different offsets: 128 bits is plenty to tell builds apart (this is a cache
// key, not a security boundary).
struct Hasher {
  uint64_t a = 1469598103934665603ull, b = 1099511628211ull * 7919ull;
  void add(const std::string& s) {
    for (unsigned char c : s) {
      a = (a ^ c) * 1099511628211ull;
      b = (b ^ c) * 1099511628211ull + 0x9e3779b97f4a7c15ull;
    }
    a = (a ^ 0xff) * 1099511628211ull;  // field separator
  }
  std::string hex() const {
    char buf[33];
    std::snprintf(buf, sizeof buf, "%016llx%016llx", static_cast<unsigned long long>(a),
                  static_cast<unsigned long long>(b));
    return buf;
  }
};

std::string tool_version(const std::string& exe, const std::string& arg) {
  const ProcessResult r = run_process({exe, arg}, "");
  return r.output.substr(0, r.output.find('\n'));
}

// Sorted files of a folder with one of the extensions, as absolute paths.
std::vector<fs::path> files_in(const fs::path& dir, const std::vector<std::string>& exts) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const std::string ext = e.path().extension().string();
    if (std::find(exts.begin(), exts.end(), ext) != exts.end()) out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

// shade_unit's sources in dependency order, leaves first (Icarus and Yosys want it too).
std::vector<fs::path> rtl_sources() {
  // SHADESIM_RTL_DIR: another copy of rtl/ (mutation testing, the cache test).
  const char* other = std::getenv("SHADESIM_RTL_DIR");
  const fs::path rtl = other && *other ? fs::path(other) : fs::path(source_dir()) / "rtl";
  std::vector<fs::path> out;
  for (const char* f :
       {"shade_pkg.sv", "fixed_round.sv", "fixed_sat.sv", "span_setup.sv", "series_engine.sv",
        "lane_fanout.sv", "pixel_combine.sv", "exponent_lut.sv", "schlick_divider.sv",
        "wpow_unit.sv", "specular_unit.sv", "fault_select.sv", "shade_unit.sv"}) {
    out.push_back(rtl / f);
  }
  return out;
}

std::vector<fs::path> harness_libraries() {
  const fs::path bin(SHADESIM_BINARY_DIR);
  return {bin / "libshadesim_harness.a", bin / "libshadesim_model.a"};
}

struct Tools {
  std::string verilator, make, cxx;
  std::string verilator_version, cxx_version;
  // Optional: with ccache the Verilator runtime (verilated.cpp, ~7 s of compiler time) compiles
  // once per machine, not once per build. It changes no output, so it is not in the cache key.
  std::string ccache;
};

Tools find_tools_now() {
  Tools t;
  t.verilator = find_program("verilator", "verilator", "rtl build (RTL on demand)");
  t.make = find_program("make", "make", "rtl build (RTL on demand)");
  t.cxx = find_program("g++", "g++", "rtl build (RTL on demand)");
  t.verilator_version = tool_version(t.verilator, "--version");
  t.cxx_version = tool_version(t.cxx, "--version");
  try {
    t.ccache = find_program("ccache", "ccache", "rtl build (optional compiler cache)");
  } catch (const std::runtime_error&) {
    t.ccache.clear();
  }
  return t;
}

// The tools and their versions cannot change while a process runs; asking once saves two child
// processes per key.
const Tools& find_tools() {
  static const Tools tools = find_tools_now();
  return tools;
}

std::string parameter_text(const std::vector<VerilogParameter>& params) {
  std::string s;
  for (const auto& p : params) s += p.name + "=" + p.literal() + " ";
  return s;
}

// The hash of every file a build is made from (the same for all builds of this process).
std::string inputs_digest() {
  Hasher h;
  const fs::path src(source_dir());
  std::vector<fs::path> inputs = rtl_sources();
  for (const auto& p : files_in(src / "sim" / "harness", {".h", ".cpp"})) inputs.push_back(p);
  for (const auto& p : files_in(src / "model", {".h"})) inputs.push_back(p);
  for (const auto& p : harness_libraries()) inputs.push_back(p);
  for (const auto& p : inputs) {
    if (!fs::exists(p)) {
      throw std::runtime_error("rtl build: " + p.string() +
                               " is missing; build the project first " + "(scripts/build)");
    }
    h.add(p.filename().string());
    h.add(read_file(p));
  }
  return h.hex();
}

std::string key_of(const RtlConfig& build, CosimBackend backend, const Tools& tools,
                   bool coverage) {
  static const std::string inputs = inputs_digest();
  Hasher h;
  // Only covered builds hash this, so the keys of plain builds (and their cache) stay as they were.
  if (coverage) {
    static const std::string cover_points = read_file(cover_points_file());  // once, like `inputs`
    h.add("coverage: line toggle user; slow code -O0");
    h.add(cover_points);
  }
  h.add(kRecipeVersion);
  h.add(parameter_text(shade_unit_parameters(build.unit, build.faults)));
  h.add(to_string(backend));
  h.add(tools.verilator_version);
  h.add(tools.cxx_version);
  h.add(inputs);
  return h.hex();
}

// Holds an exclusive flock on a file for its lifetime.
class FileLock {
 public:
  explicit FileLock(const fs::path& path) : fd_(open(path.c_str(), O_RDWR | O_CREAT, 0644)) {
    if (fd_ < 0) throw std::runtime_error("rtl build: cannot create lock " + path.string());
    while (flock(fd_, LOCK_EX) != 0) {
      if (errno != EINTR) break;  // no locking here: the atomic rename still keeps the cache whole
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

std::string generated_header(const RtlConfig& build, CosimBackend backend) {
  std::ostringstream os;
  os << "// Generated by shadesim (sim/rtl_build.cpp) for this build; do not edit.\n"
     << "// " << build.unit.to_string() << fault_text(build.faults) << " [" << to_string(backend)
     << "]\n#pragma once\n#define SHADESIM_BUILD_PARAMETERS {";
  bool first = true;
  for (const auto& p : shade_unit_parameters(build.unit, build.faults)) {
    os << (first ? "" : ", ") << "{\"" << p.name << "\", ";
    if (p.slots.empty()) {
      os << p.value;
    } else {
      os << "std::vector<int64_t>{";
      for (size_t k = 0; k < p.slots.size(); ++k) os << (k ? ", " : "") << p.slots[k];
      os << "}";
    }
    os << "}";
    first = false;
  }
  os << "}\n";
  return os.str();
}

// Verilates and compiles into `work`; returns the executable's path there.
fs::path build_into(const fs::path& work, const RtlConfig& build, CosimBackend backend,
                    const Tools& tools, int make_jobs, bool coverage, const fs::path& log) {
  const fs::path src(source_dir());
  fs::create_directories(work);
  {
    std::ofstream h(work / "cosim_build.h");
    h << generated_header(build, backend);
    if (!h)
      throw std::runtime_error("rtl build: cannot write " + (work / "cosim_build.h").string());
  }
  std::string cflags = "-std=c++17 -O2 -I" + src.string() + " -I" + work.string();
  std::string ldflags = "-pthread";
  std::vector<std::string> args = {
      tools.verilator, backend == CosimBackend::kSystemC ? "--sc" : "--cc", "--exe", "--build",
      "-j", std::to_string(std::max(1, make_jobs)), "--top-module", "shade_unit", "--prefix",
      "Vshade_unit", "-Mdir", (work / "obj").string(), "-o", "cosim", "-O3", "--x-assign", "fast",
      "--x-initial", "fast",
      // The generated makefile's default is -Os. Its "slow" files hold code that runs once
      // (construction, initial blocks, settling); in a coverage build they also register every
      // cover point, megabytes of straight-line code on which -O1 takes minutes per file
      // (own:multi: 357 s for one 4 MB file, 10 s at -O0), so coverage builds compile them
      // unoptimised.
      "-MAKEFLAGS",
      std::string("OPT_FAST=-O2 OPT_GLOBAL=-O2 OPT_SLOW=") + (coverage ? "-O0" : "-O1") +
          (tools.ccache.empty() ? std::string() : " OBJCACHE=" + tools.ccache)};
  if (backend == CosimBackend::kSystemC) cflags += " -DSHADESIM_COSIM_SYSTEMC=1";
  if (backend == CosimBackend::kCppTrace) {
    args.push_back("--trace-fst");
    cflags += " -DSHADESIM_COSIM_TRACE=1";
  }
  for (const auto& a : verilator_parameter_args(shade_unit_parameters(build.unit, build.faults))) {
    args.push_back(a);
  }
  if (coverage) {
    args.insert(args.end(), {"--coverage-line", "--coverage-toggle", "--coverage-user"});
    cflags += " -DSHADESIM_COSIM_COVERAGE=1";
  }
  for (const auto& lib : harness_libraries()) ldflags += " " + lib.string();
  if (backend == CosimBackend::kSystemC) ldflags += " -lsystemc";
  args.insert(args.end(), {"-CFLAGS", cflags, "-LDFLAGS", ldflags});
  for (const auto& p : rtl_sources()) args.push_back(p.string());
  if (coverage) args.push_back(cover_points_file());  // bound into shade_unit; no RTL file names it
  args.push_back((src / "sim" / "harness" / "cosim_adapter.cpp").string());
  const ProcessResult r = run_process(args, log.string());
  const fs::path exe = work / "obj" / "cosim";
  if (r.exit_code != 0 || !fs::exists(exe)) {
    std::string tail;
    std::ifstream is(log);
    std::vector<std::string> lines;
    for (std::string line; std::getline(is, line);) lines.push_back(line);
    for (size_t i = lines.size() > 12 ? lines.size() - 12 : 0; i < lines.size(); ++i)
      tail += "\n  " + lines[i];
    throw std::runtime_error("rtl build: Verilator/compiler failed (exit " +
                             std::to_string(r.exit_code) + "); log " + log.string() + ":" + tail);
  }
  return exe;
}

}  // namespace

std::string to_string(CosimBackend b) {
  switch (b) {
    case CosimBackend::kCpp:
      return "cpp";
    case CosimBackend::kSystemC:
      return "systemc";
    case CosimBackend::kCppTrace:
      return "cpp_trace";
  }
  return "?";
}

CosimBackend parse_cosim_backend(const std::string& s) {
  if (s == "cpp") return CosimBackend::kCpp;
  if (s == "systemc") return CosimBackend::kSystemC;
  throw std::invalid_argument("backend '" + s + "': expected cpp or systemc");
}

std::string source_dir() { return SHADESIM_SOURCE_DIR; }

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

std::string default_rtl_cache_dir() {
  return (fs::path(SHADESIM_BINARY_DIR) / "rtl-cache").string();
}

std::string rtl_build_key(const RtlConfig& build, CosimBackend backend, bool coverage) {
  return key_of(build, backend, find_tools(), coverage);
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

RtlBuildResult ensure_rtl_build(const RtlConfig& build, CosimBackend backend,
                                const RtlBuildOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  const Tools& tools = find_tools();
  RtlBuildResult r;
  r.key = key_of(build, backend, tools, o.coverage);
  // Absolute: the compiler runs in the build's own folder.
  const fs::path cache = fs::absolute(o.cache_dir.empty() ? default_rtl_cache_dir() : o.cache_dir);
  const std::string stem = to_string(backend) + (o.coverage ? "-coverage-" : "-") + r.key;
  const fs::path final_dir = cache / stem;
  const fs::path exe = final_dir / "obj" / "cosim";
  r.executable = exe.string();
  if (fs::exists(exe)) return r;

  fs::create_directories(cache);
  const fs::path lock_path = cache / (stem + ".lock");
  if (!o.quiet && !try_lock_now(lock_path)) {
    std::cerr << "rtl build: waiting for another process building " << build.name << " ("
              << to_string(backend) << ", key " << r.key.substr(0, 12) << ")" << std::endl;
  }
  FileLock lock(lock_path);
  if (fs::exists(exe)) return r;  // built by the process we waited for

  if (!o.quiet) {
    std::cerr << "rtl build: Verilating " << build.name << " [" << build.unit.to_string()
              << fault_text(build.faults) << "] for the " << to_string(backend) << " backend"
              << (o.coverage ? " with coverage" : "") << " into " << final_dir.string()
              << " (about a minute)..." << std::endl;
  }
  // Folders of builds that were killed: nobody else works on this key while we hold the lock.
  for (const auto& e : fs::directory_iterator(cache)) {
    if (e.path().filename().string().rfind(stem + ".tmp.", 0) == 0) fs::remove_all(e.path());
  }
  // Host and pid: on a cache shared over NFS two hosts can have the same pid.
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  const fs::path work = cache / (stem + ".tmp." + host + "." + std::to_string(getpid()));
  fs::create_directories(work);
  const fs::path log = work / "build.log";
  try {
    build_into(work, build, backend, tools, o.make_jobs, o.coverage, log);
  } catch (...) {
    fs::create_directories(cache / "failed");
    std::error_code ec;
    fs::copy_file(log, cache / "failed" / (stem + ".log"), fs::copy_options::overwrite_existing,
                  ec);
    fs::remove_all(work, ec);
    throw;
  }
  std::error_code ec;
  fs::rename(work, final_dir, ec);
  if (ec) {
    // Another process (without a working lock) finished first: keep its copy.
    fs::remove_all(work, ec);
    if (!fs::exists(exe))
      throw std::runtime_error("rtl build: cannot move the build into " + final_dir.string());
  }
  r.built = true;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!o.quiet) {
    std::cerr << "rtl build: " << build.name << " (" << to_string(backend)
              << (o.coverage ? ", coverage" : "") << ") built in "
              << static_cast<int>(r.seconds + 0.5) << " s" << std::endl;
  }
  return r;
}

}  // namespace shadesim
