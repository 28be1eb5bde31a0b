// The per-build part of a co-simulation executable: the Verilated shade_unit of this build on
// its backend (C++, SystemC, or C++ with FST tracing), handed to the shared driver
// (sim/harness/cosim_executable.h). sim/rtl_build.cpp compiles it with the build's Verilated
// model and its cosim_build.h (the parameters it was Verilated with).
#include <iostream>
#include <stdexcept>

#include "Vshade_unit.h"
#include "cosim_build.h"
#include "sim/harness/cosim_executable.h"

#ifdef SHADESIM_COSIM_SYSTEMC
#include "sim/harness/sc_backend.h"
#else
#include "sim/harness/cpp_backend.h"
#endif

namespace {

shadesim::CosimExecutable this_build() {
  shadesim::CosimExecutable exe;
  exe.parameters = SHADESIM_BUILD_PARAMETERS;
#ifdef SHADESIM_COSIM_COVERAGE
  exe.covered = true;
#endif
#ifdef SHADESIM_COSIM_SYSTEMC
  exe.backend = "systemc";
  exe.command = "shadesim cosim --backend systemc";
  exe.one_job_per_process = true;
  exe.run = [](const shadesim::CosimJob& job, const shadesim::WaveWindow* waves) {
    if (waves) {
      throw std::invalid_argument(
          "waveforms need the trace-enabled C++ build (shadesim cosim --waves)");
    }
    return shadesim::run_verilated_systemc<Vshade_unit>(job);
  };
#else
  exe.backend = "cpp";
#ifdef SHADESIM_COSIM_TRACE
  exe.command = "shadesim cosim --backend cpp --waves";
  exe.traced = true;
#else
  exe.command = "shadesim cosim --backend cpp";
#endif
  exe.run = [](const shadesim::CosimJob& job, const shadesim::WaveWindow* waves) {
    return shadesim::run_verilated_cpp<Vshade_unit>(job, waves);
  };
#endif
  return exe;
}

int run(int argc, char** argv) {
  const shadesim::CosimExecutable exe = this_build();
  try {
    return shadesim::cosim_main(argc, argv, exe);
  } catch (const std::exception& e) {
    std::cerr << exe.command << ": error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace

#ifdef SHADESIM_COSIM_SYSTEMC
int sc_main(int argc, char** argv) { return run(argc, argv); }
#else
int main(int argc, char** argv) { return run(argc, argv); }
#endif
