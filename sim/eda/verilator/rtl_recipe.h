// How one RTL build is made, step by step: the one home of its flags, files and commands.
// sim/eda/verilator/rtl_build.cpp decides what is cached under which key; this file only knows how.
//
// A build is four products, each made once and kept in the cache:
//   runtime   Verilator's own library (verilated.cpp, ...) and a precompiled verilated.h, per
//             flavour and optimisation: shared by every build of that flavour;
//   model     the Verilated shade_unit of one parameter set: Verilator's C++ and its objects;
//   glue      sim/harness/cosim_glue.cpp against that model (its port types);
//   link      the executable: model + glue + runtime + the harness and model libraries.
// A change to the model or the harness (their libraries) only relinks; a change to the RTL or
// the parameters Verilates again; a new compiler or Verilator rebuilds everything.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "sim/harness/rtl_config.h"

namespace shadesim {

enum class CosimBackend { kCpp, kSystemC, kCppTrace };

std::string to_string(CosimBackend b);                 // cpp, systemc, cpp_trace
CosimBackend parse_cosim_backend(const std::string&);  // cpp | systemc (throws naming the value)

// How hard the compiler works on the Verilated model: kQuick builds fastest (-O0), kFast
// simulates fastest (-O2 on the per-cycle code, -O1 in a covered build, -O0 on the code that
// runs once). See choose_optimization in sim/eda/verilator/rtl_build.h.
enum class RtlOptimization { kQuick, kFast };
std::string to_string(RtlOptimization o);  // quick | fast
RtlOptimization parse_rtl_optimization(const std::string& s);

// A backend with or without coverage: what the runtime and the glue are compiled for.
struct Flavour {
  CosimBackend backend = CosimBackend::kCpp;
  bool coverage = false;
  std::string name() const;  // cpp, systemc, cpp_trace, each with "-coverage" when covered
};

// Whether the Verilated model checks the RTL's SVA (Verilator --assert): every build but a fast
// one without coverage. A fast build is made for runs long enough to repay -O2 (a scene, a
// benchmark), and the checks slow it: Verilator samples every signal an assertion reads on each
// evaluation and checks the properties and the `unique case` items on every cycle
// (docs/history/benchmarks.md has the figures). Quick builds - every random-scenario co-simulation,
// the tests' and scripts/mutate-rtl's - and covered builds keep them; the formal proofs
// (docs/formal.md) hold them for every input.
bool checks_assertions(const Flavour& f, RtlOptimization o);

struct Toolchain {
  std::string verilator, cxx;
  std::string verilator_version, cxx_version;
  std::string verilator_root;  // its include/ holds verilated.h and the runtime sources
  bool gold = false;           // ld.gold links several times faster than ld.bfd
};

// Finds the tools; their versions are asked once per tool binary and remembered in
// `cache_dir`/tools.txt beside the stat of each binary (starting `verilator --version` costs
// 40 ms, on every run).
Toolchain find_toolchain(const std::filesystem::path& cache_dir);

// Verilator options a gate-level netlist is Verilated with, besides the RTL's (part of its
// model key). Its gates read and write single bits of wide wires, which Verilator calls circular
// (UNOPTFLAT) though no bit depends on itself; it orders them by settling, as it would a real
// loop, so the warning says nothing about the circuit. -fno-const-bit-op-tree: Verilator 5.006's
// bit-op-tree rewrite of V3Const miscompiles Yosys's XNOR-rich gate netlists (verilator#4059,
// fixed in 5.010); Icarus and Verilator -O0 run the same netlist bit-exact (docs/netlist.md).
inline const std::vector<std::string>& netlist_verilator_options() {
  static const std::vector<std::string> options = {"-Wno-UNOPTFLAT", "-fno-const-bit-op-tree"};
  return options;
}

// What a product's key is made of, besides the inputs the caller adds.
std::string recipe_text(const Flavour& f, const Toolchain& t);

// Runtime: Verilator's library objects and verilated.h precompiled for each optimisation, in
// `dir`. `jobs` compiler processes at once.
void build_runtime(const std::filesystem::path& dir, const Flavour& f, const Toolchain& t, int jobs,
                   const std::filesystem::path& log);

// Model, step 1: Verilator's C++ for `build` in `dir`/obj and its cosim_build.h (the
// parameters the glue hands to the driver) in `dir`.
void verilate(const std::filesystem::path& dir, const RtlConfig& build, const Flavour& f,
              bool assertions, const Toolchain& t, const std::vector<std::string>& rtl_sources,
              const std::string& cover_points, const std::filesystem::path& log);

// Model, step 2: the Verilated C++ of `dir`/obj compiled into objects in `out` (unity files
// balanced over `jobs` processes), with the runtime's precompiled header. Returns the objects.
std::vector<std::filesystem::path> compile_model(const std::filesystem::path& dir,
                                                 const std::filesystem::path& out, const Flavour& f,
                                                 const Toolchain& t,
                                                 const std::filesystem::path& runtime,
                                                 RtlOptimization opt, int jobs,
                                                 const std::filesystem::path& log);

// Glue: sim/harness/cosim_glue.cpp against the model in `dir`, into `object`.
void compile_glue(const std::filesystem::path& dir, const std::filesystem::path& object,
                  const Flavour& f, const Toolchain& t, const std::filesystem::path& runtime,
                  RtlOptimization opt, const std::filesystem::path& log);

// The files the glue is made from (its key).
std::vector<std::filesystem::path> glue_sources();
// The prebuilt libraries every executable links (its key); SHADESIM_HARNESS_LIB_DIR: another
// folder holding them.
std::vector<std::filesystem::path> harness_libraries();

// Link: the executable `exe` from the model's objects, the glue, the runtime and the libraries.
void link_executable(const std::filesystem::path& exe,
                     const std::vector<std::filesystem::path>& model_objects,
                     const std::filesystem::path& glue, const Flavour& f, const Toolchain& t,
                     const std::filesystem::path& runtime, const std::filesystem::path& log);

// A file's whole contents ("" when it cannot be read).
std::string read_text(const std::filesystem::path& p);

// Runs `commands` with at most `jobs` at once (output appended to `log`); throws naming the
// first that failed, with the tail of its output.
void run_commands(const std::vector<std::vector<std::string>>& commands, int jobs,
                  const std::filesystem::path& log, const std::string& what);

}  // namespace shadesim
