#include "sim/eda/verilator/rtl_recipe.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "model/rtl_parameters.h"
#include "model/text_file.h"
#include "sim/eda/common/build_paths.h"
#include "sim/eda/common/process.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

// The precompiled header every Verilated object and the glue include first.
constexpr const char* kPchName = "verilated_pch.h";

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream os(p, std::ios::binary);
  os << text;
  if (!os) throw std::runtime_error("rtl build: cannot write " + p.string());
}

// A covered build's per-cycle code is mostly toggle counting, on which -O2 spends twice -O1's
// compile for a little speed: schlick_iter_n_p4_l4_m2_mul covered, its per-cycle half compiled
// in 20.1 s at -O0, 32.3 s at -O1, 61.2 s at -O2, and multi's 302,575-cycle stream simulated in
// 152.2, 10.2 and 7.4 s (one run each, one machine).
std::string opt_flag(const Flavour& f, RtlOptimization o) {
  if (o == RtlOptimization::kQuick) return "-O0";
  return f.coverage ? "-O1" : "-O2";
}

bool systemc(const Flavour& f) { return f.backend == CosimBackend::kSystemC; }
bool traced(const Flavour& f) { return f.backend == CosimBackend::kCppTrace; }

// Verilator's VM_* switches as its own makefile sets them, and the glue's SHADESIM_COSIM_*.
std::vector<std::string> defines(const Flavour& f) {
  const auto d = [](const char* name, bool on) {
    return std::string("-D") + name + "=" + (on ? "1" : "0");
  };
  std::vector<std::string> out = {d("VM_COVERAGE", f.coverage), d("VM_SC", systemc(f)),
                                  d("VM_TRACE", traced(f)), d("VM_TRACE_FST", traced(f)),
                                  d("VM_TRACE_VCD", false)};
  if (systemc(f)) out.push_back("-DSHADESIM_COSIM_SYSTEMC=1");
  if (traced(f)) out.push_back("-DSHADESIM_COSIM_TRACE=1");
  if (f.coverage) out.push_back("-DSHADESIM_COSIM_COVERAGE=1");
  return out;
}

// The compiler command every object starts with (Verilator's own flags for its C++; warnings
// off: the code is generated).
std::vector<std::string> compiler(const Flavour& f, const Toolchain& t, RtlOptimization opt) {
  std::vector<std::string> c = {t.cxx,
                                "-std=c++17",
                                opt_flag(f, opt),
                                "-w",
                                "-faligned-new",
                                "-fcf-protection=none",
                                "-I" + t.verilator_root + "/include",
                                "-I" + t.verilator_root + "/include/vltstd"};
  for (const auto& d : defines(f)) c.push_back(d);
  return c;
}

// Verilator's library files a flavour links (its makefile's VM_GLOBAL_FAST/SLOW).
std::vector<std::string> runtime_sources(const Flavour& f) {
  std::vector<std::string> out = {"verilated", "verilated_threads"};
  if (traced(f)) out.push_back("verilated_fst_c");
  if (f.coverage) out.push_back("verilated_cov");
  return out;
}

std::string pch_text(const Flavour& f) {
  std::string s =
      "// Precompiled for every object of this flavour (sim/eda/verilator/rtl_recipe.cpp).\n";
  s += systemc(f) ? "#include \"verilated_sc.h\"\n" : "";
  s += "#include \"verilated.h\"\n";
  if (traced(f)) s += "#include \"verilated_fst_c.h\"\n";
  if (f.coverage) s += "#include \"verilated_cov.h\"\n";
  return s;
}

fs::path pch_dir(const fs::path& runtime, RtlOptimization opt) {
  return runtime / ("pch-" + to_string(opt));
}

// The flags that make an object use the runtime's precompiled header for `opt` (a header
// built with other flags would be ignored, or worse: each optimisation has its own).
std::vector<std::string> with_pch(const fs::path& runtime, RtlOptimization opt) {
  return {"-Winvalid-pch", "-I" + pch_dir(runtime, opt).string(), "-include", kPchName};
}

// `VAR += \` followed by one name a line, from Verilator's <prefix>_classes.mk.
std::vector<std::string> make_list(const std::string& mk, const std::string& var) {
  std::vector<std::string> out;
  std::istringstream is(mk);
  bool in = false;
  for (std::string line; std::getline(is, line);) {
    if (!in) {
      in = line.rfind(var + " +=", 0) == 0;
      continue;
    }
    const size_t b = line.find_first_not_of(" \t");
    if (b == std::string::npos) break;
    std::string name = line.substr(b);
    if (!name.empty() && name.back() == '\\') name.pop_back();
    while (!name.empty() && (name.back() == ' ' || name.back() == '\t')) name.pop_back();
    if (name.empty()) break;
    out.push_back(name);
  }
  return out;
}

// Splits `files` into at most `groups` unity files balanced by size (largest first, each to the
// lightest group): one compiler per core, and one precompiled-header load per group.
std::vector<std::vector<fs::path>> balance(std::vector<fs::path> files, int groups) {
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return fs::file_size(a) > fs::file_size(b);
  });
  const size_t n = std::min(files.size(), static_cast<size_t>(std::max(1, groups)));
  std::vector<std::vector<fs::path>> out(n);
  std::vector<uintmax_t> load(n, 0);
  for (const auto& f : files) {
    const size_t g = static_cast<size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    out[g].push_back(f);
    load[g] += fs::file_size(f);
  }
  return out;
}

std::string tail_of(const std::string& text, size_t lines) {
  std::vector<std::string> all;
  std::istringstream is(text);
  for (std::string l; std::getline(is, l);) all.push_back(l);
  std::string out;
  for (size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i)
    out += "\n  " + all[i];
  return out;
}

// A file's identity for the tool-version memo: path, size and modification time.
std::string stat_text(const std::string& path) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) return path + ":missing";
  return path + ":" + std::to_string(st.st_size) + ":" + std::to_string(st.st_mtim.tv_sec) + "." +
         std::to_string(st.st_mtim.tv_nsec);
}

std::string resolved(const std::string& path) {
  std::error_code ec;
  const fs::path p = fs::canonical(path, ec);
  return ec ? path : p.string();
}

}  // namespace

std::string read_text(const fs::path& p) { return read_text_file(p.string()); }

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

std::string to_string(RtlOptimization o) { return o == RtlOptimization::kFast ? "fast" : "quick"; }

RtlOptimization parse_rtl_optimization(const std::string& s) {
  if (s == "quick") return RtlOptimization::kQuick;
  if (s == "fast") return RtlOptimization::kFast;
  throw std::invalid_argument("'" + s + "': expected quick (-O0, builds fastest) or fast (-O2, " +
                              "simulates fastest)");
}

std::string Flavour::name() const { return to_string(backend) + (coverage ? "-coverage" : ""); }

Toolchain find_toolchain(const fs::path& cache_dir) {
  Toolchain t;
  const std::string what = "rtl build (RTL on demand)";
  t.verilator = find_program("verilator", "verilator", what);
  t.cxx = find_program("g++", "g++", what);
  // verilator is a script that runs verilator_bin beside it: both identify the version.
  const std::string vbin =
      (fs::path(resolved(t.verilator)).parent_path() / "verilator_bin").string();
  const std::string signature =
      stat_text(resolved(t.verilator)) + " " + stat_text(vbin) + " " + stat_text(resolved(t.cxx));
  const fs::path memo = cache_dir / "tools.txt";
  {
    // No memo yet (a new cache): ask the tools below.
    std::istringstream is(fs::exists(memo) ? read_text(memo) : std::string());
    std::string sig, vv, cv, root;
    if (std::getline(is, sig) && sig == signature && std::getline(is, vv) && std::getline(is, cv) &&
        std::getline(is, root) && !root.empty()) {
      t.verilator_version = vv;
      t.cxx_version = cv;
      t.verilator_root = root;
    }
  }
  if (t.verilator_root.empty()) {
    t.verilator_version = first_line(run_process({t.verilator, "--version"}, "").output);
    t.cxx_version = first_line(run_process({t.cxx, "--version"}, "").output);
    t.verilator_root =
        first_line(run_process({t.verilator, "--getenv", "VERILATOR_ROOT"}, "").output);
    if (t.verilator_root.empty() ||
        !fs::exists(fs::path(t.verilator_root) / "include" / "verilated.h"))
      throw std::runtime_error("rtl build: verilator --getenv VERILATOR_ROOT gave '" +
                               t.verilator_root + "', which has no include/verilated.h");
    std::error_code ec;
    fs::create_directories(cache_dir, ec);
    const fs::path tmp = memo.string() + ".tmp." + std::to_string(getpid());
    std::ofstream(tmp) << signature << '\n'
                       << t.verilator_version << '\n'
                       << t.cxx_version << '\n'
                       << t.verilator_root << '\n';
    fs::rename(tmp, memo, ec);
  }
  t.gold = access("/usr/bin/ld.gold", X_OK) == 0;
  return t;
}

bool checks_assertions(const Flavour& f, RtlOptimization o) {
  return f.coverage || o == RtlOptimization::kQuick;
}

std::string recipe_text(const Flavour& f, const Toolchain& t) {
  std::string s =
      f.name() + "|" + t.verilator_version + "|" + t.cxx_version + "|" + t.verilator_root;
  for (const auto& d : defines(f)) s += " " + d;
  if (f.coverage) s += " fast=" + opt_flag(f, RtlOptimization::kFast);  // a key per flag
  return s;
}

void run_commands(const std::vector<std::vector<std::string>>& commands, int jobs,
                  const fs::path& log, const std::string& what) {
  std::atomic<size_t> next{0};
  std::mutex m;
  std::string failure;
  std::ofstream all(log, std::ios::app);
  auto work = [&]() {
    for (size_t i = next++; i < commands.size(); i = next++) {
      const auto t0 = std::chrono::steady_clock::now();
      const ProcessResult r = run_process(commands[i], "");
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::lock_guard<std::mutex> lock(m);
      for (const auto& a : commands[i]) all << a << ' ';
      all << "\n# " << what << ": " << seconds << " s\n" << r.output;
      if (r.exit_code != 0 && failure.empty()) {
        failure = "rtl build: " + what + " failed (exit " + std::to_string(r.exit_code) +
                  "); log " + log.string() + ":" + tail_of(r.output, 12);
      }
    }
  };
  std::vector<std::thread> pool;
  const size_t n = std::min(commands.size(), static_cast<size_t>(std::max(1, jobs)));
  for (size_t w = 1; w < n; ++w) pool.emplace_back(work);
  work();
  for (auto& th : pool) th.join();
  if (!failure.empty()) throw std::runtime_error(failure);
}

void build_runtime(const fs::path& dir, const Flavour& f, const Toolchain& t, int jobs,
                   const fs::path& log) {
  std::vector<std::vector<std::string>> commands;
  for (const auto& name : runtime_sources(f)) {
    auto c = compiler(f, t, RtlOptimization::kFast);
    c.insert(c.end(), {"-c", "-o", (dir / (name + ".o")).string(),
                       t.verilator_root + "/include/" + name + ".cpp"});
    commands.push_back(c);
  }
  for (const auto opt : {RtlOptimization::kQuick, RtlOptimization::kFast}) {
    const fs::path d = pch_dir(dir, opt);
    fs::create_directories(d);
    write_text(d / kPchName, pch_text(f));
    auto c = compiler(f, t, opt);
    c.insert(c.end(), {"-x", "c++-header", "-o", (d / (std::string(kPchName) + ".gch")).string(),
                       (d / kPchName).string()});
    commands.push_back(c);
  }
  run_commands(commands, jobs, log, "the Verilator runtime (" + f.name() + ")");
}

void verilate(const fs::path& dir, const RtlConfig& build, const Flavour& f, bool assertions,
              const Toolchain& t, const std::vector<std::string>& rtl_sources,
              const std::string& cover_points, const fs::path& log) {
  const std::vector<VerilogParameter> params = shade_unit_parameters(build.unit);
  // The parameters as the glue hands them to the driver, which checks every run's unit.
  std::ostringstream h;
  h << "// Generated by shadesim (sim/eda/verilator/rtl_recipe.cpp) for this build; do not edit.\n"
    << "// " << build.unit.to_string() << fault_text(build.faults) << " [" << f.name() << "]\n"
    << "#pragma once\n";
  for (size_t i = 0; i < params.size(); ++i) {
    if (params[i].slots.empty()) continue;
    h << "static const int64_t kSlots" << i << "[] = {";
    for (size_t k = 0; k < params[i].slots.size(); ++k)
      h << (k ? ", " : "") << params[i].slots[k] << "LL";
    h << "};\n";
  }
  h << "static const shadesim::BuiltParameter kBuiltParameters[] = {\n";
  for (size_t i = 0; i < params.size(); ++i) {
    const auto& p = params[i];
    h << "    {\"" << p.name << "\", " << p.value << "LL, ";
    if (p.slots.empty()) {
      h << "nullptr, 0},\n";
    } else {
      h << "kSlots" << i << ", " << p.slots.size() << "},\n";
    }
  }
  h << "};\n";
  h << "static const bool kBuiltFaultHooks = " << (build.faults.hooks ? "true" : "false") << ";\n";
  write_text(dir / "cosim_build.h", h.str());

  std::vector<std::string> args = {t.verilator,    systemc(f) ? "--sc" : "--cc",
                                   "--top-module", "shade_unit",
                                   "--prefix",     "Vshade_unit",
                                   "-Mdir",        (dir / "obj").string(),
                                   "-O3",          "--x-assign",
                                   "fast",         "--x-initial",
                                   "fast"};
  if (assertions) args.push_back("--assert");
  if (traced(f)) args.push_back("--trace-fst");
  // The fault hooks force nets of shade_unit (sim/harness/faults/fault_hooks.sv); Verilator
  // 5.006's DFG optimisation folds a forced net into its driver and the force is lost.
  if (build.faults.hooks) args.push_back("-fno-dfg");
  if (f.coverage)
    args.insert(args.end(), {"--coverage-line", "--coverage-toggle", "--coverage-user"});
  if (build.netlist.empty()) {
    for (const auto& a : verilator_parameter_args(params)) args.push_back(a);
    for (const auto& s : rtl_sources) args.push_back(s);
  } else {
    // Yosys's flat netlist: the parameters are baked in (no -G), the one file is the unit.
    for (const auto& o : netlist_verilator_options()) args.push_back(o);
    args.push_back(build.netlist);
  }
  if (f.coverage) args.push_back(cover_points);  // bound into shade_unit; no RTL file names it
  run_commands({args}, 1, log, "Verilator");
  // The runtime must hold every library file this model asks for.
  const std::string mk = read_text(dir / "obj" / "Vshade_unit_classes.mk");
  const std::vector<std::string> have = runtime_sources(f);
  for (const char* var : {"VM_GLOBAL_FAST", "VM_GLOBAL_SLOW"}) {
    for (const auto& g : make_list(mk, var)) {
      if (std::find(have.begin(), have.end(), g) == have.end())
        throw std::runtime_error(
            "rtl build: the Verilated model needs " + g + ".cpp, which the " + f.name() +
            " runtime lacks (sim/eda/verilator/rtl_recipe.cpp runtime_sources)");
    }
  }
}

std::vector<fs::path> compile_model(const fs::path& dir, const fs::path& out, const Flavour& f,
                                    const Toolchain& t, const fs::path& runtime,
                                    RtlOptimization opt, int jobs, const fs::path& log) {
  const fs::path obj = dir / "obj";
  const std::string mk = read_text(obj / "Vshade_unit_classes.mk");
  std::vector<fs::path> fast, slow;
  for (const char* var : {"VM_CLASSES_FAST", "VM_SUPPORT_FAST"})
    for (const auto& n : make_list(mk, var)) fast.push_back(obj / (n + ".cpp"));
  for (const char* var : {"VM_CLASSES_SLOW", "VM_SUPPORT_SLOW"})
    for (const auto& n : make_list(mk, var)) slow.push_back(obj / (n + ".cpp"));
  // The code that runs once (construction, settling, and in covered builds the registration of
  // every cover point: megabytes on which -O1 took minutes) is not worth optimising; in a
  // quick build nothing is.
  struct Part {
    std::vector<fs::path> files;
    RtlOptimization opt;
  };
  std::vector<Part> parts;
  if (opt == RtlOptimization::kQuick) {
    std::vector<fs::path> all = fast;
    all.insert(all.end(), slow.begin(), slow.end());
    for (auto& g : balance(all, jobs)) parts.push_back({g, RtlOptimization::kQuick});
  } else {
    for (auto& g : balance(fast, jobs)) parts.push_back({g, RtlOptimization::kFast});
    for (auto& g : balance(slow, 1)) parts.push_back({g, RtlOptimization::kQuick});
  }
  fs::create_directories(out);
  std::vector<std::vector<std::string>> commands;
  std::vector<fs::path> objects;
  for (size_t i = 0; i < parts.size(); ++i) {
    const fs::path unity = out / ("unity" + std::to_string(i) + ".cpp");
    std::string text;
    for (const auto& file : parts[i].files) text += "#include \"" + file.string() + "\"\n";
    write_text(unity, text);
    auto c = compiler(f, t, parts[i].opt);
    const auto pch = with_pch(runtime, parts[i].opt);
    c.insert(c.end(), pch.begin(), pch.end());
    objects.push_back(out / ("unity" + std::to_string(i) + ".o"));
    c.insert(c.end(), {"-I" + obj.string(), "-c", "-o", objects.back().string(), unity.string()});
    commands.push_back(c);
  }
  run_commands(commands, jobs, log, "compiling the Verilated model");
  return objects;
}

std::vector<fs::path> glue_sources() {
  const fs::path h = fs::path(source_dir()) / "sim" / "harness";
  return {h / "cosim_glue.cpp", h / "verilated_dut.h", h / "sc_dut.h"};
}

std::vector<fs::path> harness_libraries() {
  // SHADESIM_HARNESS_LIB_DIR: another copy of the libraries (the relink test).
  const char* other = std::getenv("SHADESIM_HARNESS_LIB_DIR");
  const fs::path bin = other && *other ? fs::path(other) : fs::path(binary_dir());
  return {bin / "libshadesim_harness.a", bin / "libshadesim_model.a"};
}

void compile_glue(const fs::path& dir, const fs::path& object, const Flavour& f, const Toolchain& t,
                  const fs::path& runtime, RtlOptimization opt, const fs::path& log) {
  auto c = compiler(f, t, opt);
  const auto pch = with_pch(runtime, opt);
  c.insert(c.end(), pch.begin(), pch.end());
  c.insert(c.end(), {"-I" + source_dir(), "-I" + dir.string(), "-I" + (dir / "obj").string(), "-c",
                     "-o", object.string(), glue_sources().front().string()});
  run_commands({c}, 1, log, "compiling the co-simulation glue");
}

void link_executable(const fs::path& exe, const std::vector<fs::path>& model_objects,
                     const fs::path& glue, const Flavour& f, const Toolchain& t,
                     const fs::path& runtime, const fs::path& log) {
  std::vector<std::string> c = {t.cxx};
  if (t.gold) c.push_back("-fuse-ld=gold");
  c.push_back(glue.string());
  for (const auto& o : model_objects) c.push_back(o.string());
  for (const auto& name : runtime_sources(f)) c.push_back((runtime / (name + ".o")).string());
  for (const auto& lib : harness_libraries()) c.push_back(lib.string());
  c.insert(c.end(), {"-pthread", "-latomic"});
  if (systemc(f)) c.push_back("-lsystemc");
  if (traced(f)) c.push_back("-lz");
  c.insert(c.end(), {"-o", exe.string()});
  run_commands({c}, 1, log, "linking the co-simulation executable");
}

}  // namespace shadesim
