// The per-build part of a co-simulation executable: this build's Verilated shade_unit behind
// CppDut or ScDut (sim/harness/verilated_dut.h, sc_dut.h), and a main that hands it to the loop
// and driver compiled once in the harness libraries. sim/eda/verilator/rtl_build.cpp compiles it
// with the build's Verilated model, its flavour's defines (SHADESIM_COSIM_SYSTEMC, _TRACE,
// _COVERAGE) and its generated cosim_build.h (the parameters it was Verilated with).
//
// Port types follow the parameters (Verilator picks CData ... QData, or VlWide above 64 bits;
// bool ... uint64_t or sc_bv in SystemC): the overloads below take each of them.
#include <stdexcept>
#include <string>

#include "Vshade_unit.h"
#include "verilated.h"
#ifdef SHADESIM_COSIM_SYSTEMC
#include "sim/harness/sc_dut.h"
#else
#include "sim/harness/verilated_dut.h"
#endif
#include "cosim_build.h"  // after verilated_dut.h: it lists shadesim::BuiltParameter
#ifdef SHADESIM_COSIM_TRACE
#include "verilated_fst_c.h"
#endif
#ifdef SHADESIM_COSIM_COVERAGE
#include "verilated_cov.h"
#endif

namespace {

// Bits [lsb, lsb + width) of an integer port (width <= 64).
inline uint64_t bits_of(uint64_t port, int lsb, int width) {
  const uint64_t v = port >> lsb;
  return width >= 64 ? v : v & ((uint64_t{1} << width) - 1);
}

#ifndef SHADESIM_COSIM_SYSTEMC
// A beat (port_words 64-bit words) on cmd_data_i: a 64-bit port for one word, a VlWide of
// 32-bit words for more.
inline void put_beat(QData& port, const uint64_t* beat, int /*port_words*/) { port = beat[0]; }
template <std::size_t N>
inline void put_beat(VlWide<N>& port, const uint64_t* beat, int port_words) {
  for (int k = 0; k < port_words; ++k) {
    port[2 * k] = static_cast<EData>(beat[k]);
    port[2 * k + 1] = static_cast<EData>(beat[k] >> 32);
  }
}
inline bool fits(const QData&, int port_words) { return port_words == 1; }
template <std::size_t N>
inline bool fits(const VlWide<N>&, int port_words) {
  return N == 2 * static_cast<std::size_t>(port_words);
}
inline uint64_t colour_of(uint64_t port, int lsb, int width) { return bits_of(port, lsb, width); }
template <std::size_t N>
inline uint64_t colour_of(const VlWide<N>& port, int lsb, int width) {
  uint64_t v = 0;
  for (int b = 0; b < width; ++b) {
    const int i = lsb + b;
    v |= static_cast<uint64_t>((port[static_cast<std::size_t>(i / 32)] >> (i % 32)) & 1U) << b;
  }
  return v;
}

class Dut final : public shadesim::CppDut {
 public:
  Dut(int argc, const char** argv) {
    context_.commandArgs(argc, argv);
    top_ = std::make_unique<Vshade_unit>(&context_);
  }
  bool port_fits(int port_words) const override { return fits(top_->cmd_data_i, port_words); }
  void set_clock(bool clk) override { top_->clk_i = clk; }
  void set_reset_n(bool rst_n) override { top_->rst_ni = rst_n; }
  void set_inputs(bool cmd_valid, const uint64_t* beat, int port_words, bool pix_ready) override {
    top_->cmd_valid_i = cmd_valid;
    put_beat(top_->cmd_data_i, beat, port_words);
    top_->pix_ready_i = pix_ready;
  }
  void eval() override { top_->eval(); }
  shadesim::DutOutputs outputs() const override {
    shadesim::DutOutputs o;
    o.cmd_ready = top_->cmd_ready_o;
    o.pix_valid = top_->pix_valid_o;
    o.pix_x = top_->pix_x_o;
    o.pix_y = top_->pix_y_o;
    o.pix_mask = top_->pix_mask_o;
    o.pix_eor = top_->pix_eor_o;
    return o;
  }
  shadesim::DutOutputs settle(bool cmd_valid, const uint64_t* beat, int port_words,
                              bool pix_ready) override {
    set_inputs(cmd_valid, beat, port_words, pix_ready);
    top_->eval();
    return outputs();
  }
  void rising_edge() override {
    top_->clk_i = 1;
    top_->eval();
    top_->clk_i = 0;
  }
  uint64_t colour_bits(int lsb, int width) const override {
    return colour_of(top_->pix_colour_o, lsb, width);
  }
#ifdef SHADESIM_COSIM_TRACE
  void open_trace(const std::string& path) override {
    context_.traceEverOn(true);
    fst_ = std::make_unique<VerilatedFstC>();
    top_->trace(fst_.get(), 99);
    fst_->open(path.c_str());
    if (!fst_->isOpen()) throw std::runtime_error(path + ": cannot open for writing the waveform");
  }
  void dump(uint64_t time) override { fst_->dump(time); }
  void close_trace() override { fst_->close(); }
#else
  void open_trace(const std::string&) override {
    throw std::invalid_argument(
        "waveforms need the trace-enabled build (shadesim cosim --waves picks it); this one has "
        "no tracing");
  }
  void dump(uint64_t) override {}
  void close_trace() override {}
#endif
  void write_coverage(const std::string& path) override {
#ifdef SHADESIM_COSIM_COVERAGE
    context_.coveragep()->write(path.c_str());
#else
    (void)path;
#endif
  }
  void final() override { top_->final(); }

 private:
  VerilatedContext context_;
  std::unique_ptr<Vshade_unit> top_;
#ifdef SHADESIM_COSIM_TRACE
  std::unique_ptr<VerilatedFstC> fst_;
#endif
};

#else  // SystemC

inline void to_port(uint64_t& port, const uint64_t* beat, int /*port_words*/) { port = beat[0]; }
template <int W>
inline void to_port(sc_dt::sc_bv<W>& port, const uint64_t* beat, int port_words) {
  static_assert(W % 64 == 0, "cmd_data_i is a whole number of 64-bit words");
  for (int k = 0; k < port_words && 64 * k < W; ++k) {
    port.set_word(2 * k, static_cast<sc_dt::sc_digit>(beat[k]));
    port.set_word(2 * k + 1, static_cast<sc_dt::sc_digit>(beat[k] >> 32));
  }
}
inline bool fits(const uint64_t&, int port_words) { return port_words == 1; }
template <int W>
inline bool fits(const sc_dt::sc_bv<W>&, int port_words) {
  return W == 64 * port_words;
}
inline uint64_t colour_of(uint64_t port, int lsb, int width) { return bits_of(port, lsb, width); }
template <int W>
inline uint64_t colour_of(const sc_dt::sc_bv<W>& port, int lsb, int width) {
  return port.range(lsb + width - 1, lsb).to_uint64();
}

// Verilator picks bool / uint32_t / uint64_t / sc_bv per port width; follow it.
template <class Port>
using DataOf = typename std::remove_reference_t<Port>::data_type;
using XT = DataOf<decltype(std::declval<Vshade_unit&>().pix_x_o)>;
using CT = DataOf<decltype(std::declval<Vshade_unit&>().pix_colour_o)>;
using DT = DataOf<decltype(std::declval<Vshade_unit&>().cmd_data_i)>;
using MT = DataOf<decltype(std::declval<Vshade_unit&>().pix_mask_o)>;

class Dut final : public shadesim::ScDut {
 public:
  Dut(sc_core::sc_clock& clk, int argc, const char** argv) {
    Verilated::commandArgs(argc, argv);
    dut_ = std::make_unique<Vshade_unit>("dut");
    dut_->clk_i(clk);
    dut_->rst_ni(rst_n_);
    dut_->cmd_data_i(cmd_data_);
    dut_->cmd_valid_i(cmd_valid_);
    dut_->cmd_ready_o(cmd_ready_);
    dut_->pix_x_o(pix_x_);
    dut_->pix_y_o(pix_y_);
    dut_->pix_colour_o(pix_colour_);
    dut_->pix_mask_o(pix_mask_);
    dut_->pix_eor_o(pix_eor_);
    dut_->pix_valid_o(pix_valid_);
    dut_->pix_ready_i(pix_ready_);
  }
  bool port_fits(int port_words) const override { return fits(DT{}, port_words); }
  void write_inputs(bool rst_n, bool cmd_valid, const uint64_t* beat, int port_words,
                    bool pix_ready) override {
    rst_n_.write(rst_n);
    cmd_valid_.write(cmd_valid);
    DT data{};
    to_port(data, beat, port_words);
    cmd_data_.write(data);
    pix_ready_.write(pix_ready);
  }
  shadesim::DutOutputs read_outputs() const override {
    shadesim::DutOutputs o;
    o.cmd_ready = cmd_ready_.read();
    o.pix_valid = pix_valid_.read();
    o.pix_x = pix_x_.read();
    o.pix_y = pix_y_.read();
    o.pix_mask = static_cast<uint64_t>(pix_mask_.read());
    o.pix_eor = pix_eor_.read();
    return o;
  }
  uint64_t colour_bits(int lsb, int width) const override {
    return colour_of(pix_colour_.read(), lsb, width);
  }
  void write_coverage(const std::string& path) override {
#ifdef SHADESIM_COSIM_COVERAGE
    // The counters live in the model (counted into the thread's context).
    Verilated::threadContextp()->coveragep()->write(path.c_str());
#else
    (void)path;
#endif
  }

 private:
  sc_core::sc_signal<bool> rst_n_{"rst_n"}, cmd_valid_{"cmd_valid"}, cmd_ready_{"cmd_ready"};
  sc_core::sc_signal<DT> cmd_data_{"cmd_data"};
  sc_core::sc_signal<XT> pix_x_{"pix_x"}, pix_y_{"pix_y"};
  sc_core::sc_signal<CT> pix_colour_{"pix_colour"};
  sc_core::sc_signal<MT> pix_mask_{"pix_mask"};
  sc_core::sc_signal<bool> pix_eor_{"pix_eor"}, pix_valid_{"pix_valid"}, pix_ready_{"pix_ready"};
  std::unique_ptr<Vshade_unit> dut_;
};

#endif

shadesim::BuiltModel this_model() {
  shadesim::BuiltModel m;
  m.parameters = kBuiltParameters;
  m.parameter_count = static_cast<int>(sizeof kBuiltParameters / sizeof kBuiltParameters[0]);
  m.fault_hooks = kBuiltFaultHooks;
#ifdef SHADESIM_COSIM_TRACE
  m.traced = true;
#endif
#ifdef SHADESIM_COSIM_COVERAGE
  m.covered = true;
#endif
  return m;
}

}  // namespace

namespace shadesim {
#ifdef SHADESIM_COSIM_SYSTEMC
std::unique_ptr<ScDut> make_sc_dut(sc_core::sc_clock& clk, int argc, const char** argv) {
  return std::make_unique<Dut>(clk, argc, argv);
}
#else
std::unique_ptr<CppDut> make_cpp_dut(int argc, const char** argv) {
  return std::make_unique<Dut>(argc, argv);
}
#endif
}  // namespace shadesim

#ifdef SHADESIM_COSIM_SYSTEMC
int sc_main(int argc, char** argv) { return shadesim::sc_cosim_main(argc, argv, this_model()); }
#else
int main(int argc, char** argv) { return shadesim::cpp_cosim_main(argc, argv, this_model()); }
#endif
