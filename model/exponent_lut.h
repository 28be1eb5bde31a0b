// ExponentLut: t^n from a table (Bishop & Weimer). Mirrors rtl/exponent_lut.sv.
//
// Parameters (LutConfig, same names in RTL): A = addr_bits (2^A entries), B = entry_bits (entry e
// means e / 2^B, so the largest value is 1 - 2^-B), F = interp_bits (0 = no interpolation),
// index rule (truncate | nearest). The series format (frac bits fs) comes from the unit config.
// Per material (MATERIAL unit_params): [0] = shift, 0..fs (input pre-scale, see below).
//
// The series carries x = v * D / N, pre-scaled at setup by 2^-shift: v in [0, 1] is the table
// argument (t for a per-exponent table; u / U for the shared exp table), N = 2^A, and D = N when
// the entries sit at cell centres (truncate, no interpolation) or N - 1 when they sit on cell
// edges (nearest, or interpolation). So the address is the series' bits below the binary point
// moved up by A (+ shift): no multiplier in the datapath.
//
// Stages (one register each in RTL):
//   1. ADDRESS  a = quantize(series << shift, to unsigned A.F, rule = index rule, saturate):
//               t < 0 gives entry 0, t > 1 saturates to entry N-1 (and fraction all-ones).
//               idx = a >> F, frac = a & (2^F - 1).
//   2. READ     e0 = table[idx]; with F > 0 also e1 = table[min(idx + 1, N - 1)] (second port).
//   3. INTERP   (F > 0 only) v = e0 * 2^F + frac * (e1 - e0), exact (B + F fraction bits; one
//               (F+1) x (B+1) signed multiplier).
//   4. OUTPUT   quantize(v) into the specular out format.
// Latency: 2 cycles (address, read) + 1 with interpolation; one pixel per cycle.
// Table entries are loaded by TABLE commands (per-exponent: on every material switch, N words;
// shared: once), and written by write_hex() as the $readmemh file the RTL loads.
// Material banks (`banks` = UnitConfig::material_buffers, RTL BANKS): with 2 there are two
// tables, as there are two shift registers. Each MATERIAL switches to the other bank
// (next_material); a per-material TABLE (TableCmd::per_material) writes the current bank's
// table, any other TABLE both; a pixel reads the table of the bank current when its span was
// taken - in stream order, the current one. So a per-exponent reload after a MATERIAL loads
// while the previous material's pixels still read the other table.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/command_stream.h"
#include "model/fixed_point.h"
#include "model/specular_config.h"

namespace shadesim {

class ExponentLut {
 public:
  ExponentLut(const LutConfig& config, const FixedFormat& series, const FixedFormat& out,
              int banks = 1);

  // unit_params = [shift]; empty means shift 0. Throws std::invalid_argument when out of range.
  void load_params(const std::vector<int64_t>& unit_params);
  // A MATERIAL: the next material's parameters and per-material table go to the other bank.
  void next_material() { bank_ = (bank_ + 1) % static_cast<int>(tables_.size()); }
  // Writes entries base..base+size-1. Throws std::invalid_argument naming the address when an
  // entry is outside 0..2^B-1 or the address is past the table.
  void load_table(const TableCmd& t);

  int64_t evaluate(int64_t series_raw) const;

  int entries() const { return 1 << config_.addr_bits; }
  // The current bank's table.
  const std::vector<int64_t>& table() const { return tables_[static_cast<size_t>(bank_)]; }
  // $readmemh text: one entry per line, ceil(B/4) hex digits. Throws std::runtime_error naming
  // the path when it cannot be written.
  void write_hex(const std::string& path) const;

  // --- geometry shared with setup (host/specular_setup) ---
  // D / N: setup multiplies the table argument v by this to form the series value x.
  static double argument_scale(const LutConfig& c);
  // The argument v at which entry i is sampled (cell centre or edge, see above).
  static double sample_argument(const LutConfig& c, int i);

  // --- cost ---
  static int64_t table_bits(const LutConfig& c) {
    return (int64_t{1} << c.addr_bits) * c.entry_bits;
  }
  static int multipliers(const LutConfig& c) { return c.interp_bits > 0 ? 1 : 0; }
  static int latency(const LutConfig& c) { return c.interp_bits > 0 ? 3 : 2; }
  static int cycles_per_pixel(const LutConfig&) { return 1; }
  // Cycles to reload the table on a material switch (one entry per cycle); 0 when shared.
  static int64_t reload_cycles(const LutConfig& c) {
    return c.addressing == LutAddressing::kPerExponent ? (int64_t{1} << c.addr_bits) : 0;
  }

 private:
  LutConfig config_;
  FixedFormat series_;
  FixedFormat out_;
  FixedFormat address_;  // unsigned A.F, index rule, saturating
  int shift_ = 0;        // the current bank's (the other bank's is never read again: MATERIAL
                         // always loads the shift)
  std::vector<std::vector<int64_t>> tables_;  // per material bank
  int bank_ = 0;
};

}  // namespace shadesim
