// Drives one Verilated specular unit (or specular_unit) and checks it against the model class,
// every output bit and the exact timing contract (rtl/specular_unit.sv):
//   pipelined (II 1): spec_o is the result for the input sampled at the LATENCY-th most recent
//                     en_i edge, with en_i toggled at random (stalls hold the pipe);
//   iterative (II = LATENCY): busy_o high exactly LATENCY-1 cycles after a start, result from
//                     cycle start+LATENCY until the next start's edge, en_i ignored while busy.
// The configurations and their parameters come from cmake/rtl_units.cmake (generated header).
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "model/fixed_point.h"
#include "model/specular_units.h"
#include "rtl_units_configs.inc"

namespace shadesim {
namespace rtl_units {

using Params = std::map<std::string, int64_t>;

// "ADDR_BITS=4 ENTRY_BITS=6 ..." as CMake wrote it.
inline Params parse_params(const std::string& text) {
  Params p;
  std::istringstream is(text);
  std::string item;
  while (is >> item) {
    const auto eq = item.find('=');
    if (eq == std::string::npos) throw std::runtime_error("bad parameter text: " + item);
    p[item.substr(0, eq)] = std::stoll(item.substr(eq + 1));
  }
  return p;
}

inline Params config_params(const std::string& name) {
  static const std::map<std::string, std::string> table = {
#define SHADESIM_RTL_UNIT_ENTRY(n, text) {#n, text},
      SHADESIM_RTL_UNIT_CONFIGS(SHADESIM_RTL_UNIT_ENTRY)
#undef SHADESIM_RTL_UNIT_ENTRY
  };
  const auto it = table.find(name);
  if (it == table.end()) throw std::runtime_error("no RTL unit configuration " + name);
  return parse_params(it->second);
}

inline int64_t get(const Params& p, const std::string& key) {
  const auto it = p.find(key);
  if (it == p.end()) throw std::runtime_error("RTL unit configuration lacks " + key);
  return it->second;
}

// The unit's fields from the configuration's SLOTk entries (SPEC_PARAMS slot k,
// cmake/rtl_units.cmake) through the unit's row of model/specular_units.cpp: the slots the RTL
// module decodes must be the row's, or the model built here is not the unit the RTL is.
inline SpecularConfig unit_fields(const Params& p, SpecularUnitKind kind) {
  SpecularConfig s;
  s.kind = kind;
  for (const SpecularField& f : specular_unit(kind).fields) {
    if (f.slot >= 0) f.set(s, static_cast<int>(get(p, "SLOT" + std::to_string(f.slot))));
  }
  return s;
}

// The series format (signed; its own rounding/overflow rules do not matter to the units).
inline FixedFormat series_format(const Params& p, const std::string& prefix = "") {
  return FixedFormat{static_cast<int>(get(p, prefix + "SERIES_WL")),
                     static_cast<int>(get(p, prefix + "SERIES_IWL")), true, Quantization::kTruncate,
                     Overflow::kWrap};
}

inline FixedFormat out_format(const Params& p, const std::string& prefix) {
  auto opt = [&](const std::string& k) {
    const auto it = p.find(prefix + k);
    return it == p.end() ? 0 : it->second;
  };
  return FixedFormat{static_cast<int>(get(p, prefix + "WL")),
                     static_cast<int>(get(p, prefix + "IWL")), false,
                     opt("QUANT") ? Quantization::kRoundNearest : Quantization::kTruncate,
                     opt("OVERFLOW") ? Overflow::kWrap : Overflow::kSaturate};
}

inline uint64_t to_bits(int64_t raw, int wl) {
  return wl >= 64 ? static_cast<uint64_t>(raw)
                  : static_cast<uint64_t>(raw) & ((uint64_t{1} << wl) - 1);
}

// Hard-case raw series values for a format: 0, +-1 LSB, the extremes, t = +-1 and its neighbours,
// and the edges of every power of two below 1 (address/operand boundaries for any shift).
inline std::vector<int64_t> hard_series(const FixedFormat& f) {
  std::vector<int64_t> v = {0, 1, -1, f.raw_max(), f.raw_min(), f.raw_max() - 1, f.raw_min() + 1};
  for (int b = 0; b < f.wl - 1; ++b) {
    const int64_t x = int64_t{1} << b;
    for (int64_t d : {-1, 0, 1}) {
      v.push_back(x + d);
      v.push_back(-x + d);
    }
  }
  return v;
}

struct Mismatch {
  int64_t count = 0;
  std::string first;
  void add(const std::string& what) {
    if (count++ == 0) first = what;
  }
};

// Generic clocking for a Verilated unit with clk_i, rst_ni, en_i, spec_o (and busy_o for units
// that have it). `set_input(dut, k)` drives input k (k < 0: arbitrary filler); `expected(k)` is
// the model's output for input k; `describe(k)` names it in a failure.
template <class V>
void reset(V& dut) {
  dut.clk_i = 0;
  dut.en_i = 0;
  dut.rst_ni = 0;
  dut.eval();
  dut.rst_ni = 1;
  dut.eval();
}

template <class V>
void clock_edge(V& dut) {
  dut.clk_i = 1;
  dut.eval();
  dut.clk_i = 0;
}

template <class V>
struct UnitRun {
  V& dut;
  int latency;
  std::mt19937_64& rng;
  std::function<void(int64_t)> set_input;
  std::function<int64_t(int64_t)> expected;
  std::function<std::string(int64_t)> describe;
  std::function<bool()> busy = [] { return false; };
  Mismatch* mismatch;
  int64_t cycles = 0;

  // Pipelined contract; en_i high with probability en_pct %.
  void pipelined(int64_t n, int en_pct) {
    std::deque<int64_t> hist;  // input index per en edge, -1 = filler (flush)
    int64_t next = 0;
    int64_t pushed = 0;
    while (pushed < n + latency) {
      const bool en = static_cast<int>(rng() % 100) < en_pct;
      const int64_t k = next < n ? next : -1;
      set_input(k);
      dut.en_i = en;
      dut.eval();
      if (busy())
        mismatch->add("busy_o high in a pipelined unit at cycle " + std::to_string(cycles));
      if (static_cast<int>(hist.size()) >= latency) {
        const int64_t j = hist[hist.size() - static_cast<size_t>(latency)];
        if (j >= 0) {
          const int64_t want = expected(j);
          const int64_t got = static_cast<int64_t>(dut.spec_o);
          if (want != got) {
            mismatch->add(describe(j) + ": expected " + std::to_string(want) + ", got " +
                          std::to_string(got) + " (cycle " + std::to_string(cycles) + ")");
          }
        }
      }
      clock_edge(dut);
      ++cycles;
      if (en) {
        hist.push_back(k);
        if (hist.size() > static_cast<size_t>(latency) + 1) hist.pop_front();
        ++pushed;
        if (next < n) ++next;
      }
    }
    dut.en_i = 0;
  }

  // Iterative contract: start, LATENCY-1 busy cycles (en_i driven at random, must be ignored,
  // with a different input), result from start + LATENCY on, held for 0..2 extra cycles, then the
  // next start in the same cycle the result is still visible.
  void iterative(int64_t n) {
    int64_t prev = -1;
    for (int64_t k = 0; k < n; ++k) {
      set_input(k);
      dut.en_i = 1;
      dut.eval();
      if (busy()) mismatch->add("busy_o high at the start of " + describe(k));
      if (prev >= 0 && static_cast<int64_t>(dut.spec_o) != expected(prev)) {
        mismatch->add(describe(prev) + ": result not held until the next start");
      }
      clock_edge(dut);
      ++cycles;
      for (int c = 1; c < latency; ++c) {
        set_input(-1);
        dut.en_i = rng() & 1;
        dut.eval();
        if (!busy()) {
          mismatch->add(describe(k) + ": busy_o low " + std::to_string(c) + " cycles after start");
        }
        clock_edge(dut);
        ++cycles;
      }
      const int hold = static_cast<int>(rng() % 3);
      for (int h = 0; h <= hold; ++h) {
        dut.en_i = 0;
        dut.eval();
        if (busy()) mismatch->add(describe(k) + ": busy_o still high at start + LATENCY");
        const int64_t want = expected(k);
        const int64_t got = static_cast<int64_t>(dut.spec_o);
        if (want != got) {
          mismatch->add(describe(k) + ": expected " + std::to_string(want) + ", got " +
                        std::to_string(got) + " (" + std::to_string(h) +
                        " cycles after start + LATENCY)");
        }
        if (h < hold) {
          clock_edge(dut);
          ++cycles;
        }
      }
      prev = k;
    }
  }
};

}  // namespace rtl_units
}  // namespace shadesim
