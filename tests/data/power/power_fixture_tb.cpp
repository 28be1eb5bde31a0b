// Drives tests/data/power/power_fixture.sv as the co-simulation harness drives shade_unit
// (sim/harness/cpp_backend.cpp) and traces it as `--trace-run` does: every input low and rst_ni
// low for 4 reset edges, then per cycle c the inputs set and evaluated (an FST sample at
// 10 (c + 4)), the rising edge evaluated (a sample 5 later), the clock lowered. d_i follows
// 1, 1, 0, 0, 1, 1, 0, 0, ... Usage: power_fixture_tb FILE.fst CYCLES [COVERAGE.dat]. Built by
// tests/power_test.cpp with Verilator --trace-fst and --coverage-toggle (whose counts, from the
// first evaluation on, go to COVERAGE.dat).
#include <cstdint>
#include <cstdlib>

#include "Vpower_fixture.h"
#include "verilated.h"
#include "verilated_cov.h"
#include "verilated_fst_c.h"

int main(int argc, char** argv) {
  if (argc < 3) return 2;
  const int cycles = std::atoi(argv[2]);
  VerilatedContext context;
  context.traceEverOn(true);
  Vpower_fixture top(&context);
  VerilatedFstC fst;
  top.trace(&fst, 99);
  top.clk_i = 0;
  top.rst_ni = 0;
  top.d_i = 0;
  top.eval();
  for (int i = 0; i < 4; ++i) {
    top.clk_i = 1;
    top.eval();
    top.clk_i = 0;
    top.eval();
  }
  top.rst_ni = 1;
  fst.open(argv[1]);
  for (int c = 0; c < cycles; ++c) {
    const uint64_t t = 10 * static_cast<uint64_t>(c + 4);
    top.d_i = (c / 2) % 2 == 0 ? 1 : 0;
    top.eval();
    fst.dump(t);
    top.clk_i = 1;
    top.eval();
    fst.dump(t + 5);
    top.clk_i = 0;
  }
  fst.close();
  top.final();
  if (argc > 3) context.coveragep()->write(argv[3]);
  return 0;
}
