// ExponentLut against double precision: exhaustive sweeps at small widths, a derived error bound
// against t^n at production widths, the table ends, the hex file and bad TABLE commands.
#include "model/exponent_lut.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "host/specular_setup.h"
#include "model/specular_unit.h"

namespace shadesim {
namespace {

const FixedFormat kOut{17, 1, false, Quantization::kTruncate, Overflow::kSaturate};

// The unit's output for series value x (already pre-scaled), in double, computed directly from
// the stage description with floor/clamp in double (exact at these small widths).
double reference(const LutConfig& c, const std::vector<int64_t>& table, double x) {
  const double n = std::ldexp(1.0, c.addr_bits);
  const double a = x * n;
  const double scale = std::ldexp(1.0, c.interp_bits);
  double aq = c.index == LutIndex::kTruncate ? std::floor(a * scale) : std::floor(a * scale + 0.5);
  aq = std::clamp(aq / scale, 0.0, n - 1.0 / scale);
  const double idx = std::floor(aq);
  const double frac = aq - idx;
  const double e0 = static_cast<double>(table[static_cast<size_t>(idx)]);
  const double e1 = static_cast<double>(table[static_cast<size_t>(std::min(idx + 1, n - 1))]);
  const double v = (e0 + frac * (e1 - e0)) / std::ldexp(1.0, c.entry_bits);
  return std::floor(v * 65536.0) / 65536.0;  // out u1.16, truncate
}

TEST(ExponentLut, ExhaustiveSmallWidthsMatchDoubleReference) {
  const FixedFormat series{16, 4, true, Quantization::kTruncate, Overflow::kWrap};  // s4.12
  for (LutIndex rule : {LutIndex::kTruncate, LutIndex::kNearest}) {
    for (int f : {0, 3}) {
      for (int shift : {0, 2}) {
        LutConfig c;
        c.addr_bits = 4;
        c.entry_bits = 6;
        c.interp_bits = f;
        c.index = rule;
        ExponentLut lut(c, series, kOut);
        lut.load_params({shift});
        const std::vector<int64_t> table = lut_entries(c, 3.0);
        lut.load_table(to_table_commands(table)[0]);
        for (int64_t raw = series.raw_min(); raw <= series.raw_max(); ++raw) {
          const double x = std::ldexp(static_cast<double>(raw), -(series.frac_bits() - shift));
          ASSERT_EQ(kOut.to_double(lut.evaluate(raw)), reference(c, table, x))
              << "raw " << raw << " rule " << to_string(rule) << " F " << f << " shift " << shift;
        }
      }
    }
  }
}

TEST(ExponentLut, EntriesAreRoundedSamplesOfPow) {
  LutConfig c;
  c.addr_bits = 6;
  c.entry_bits = 8;
  for (double n : {1.0, 2.5, 40.0}) {
    const auto e = lut_entries(c, n);
    for (int i = 0; i < 64; ++i) {
      const double want = std::min(255.0, std::floor(std::pow((i + 0.5) / 64.0, n) * 256.0 + 0.5));
      EXPECT_EQ(static_cast<double>(e[static_cast<size_t>(i)]), want) << "n " << n << " i " << i;
    }
  }
}

// Bound derived from the geometry: nearest-entry (cell-centre) sampling misses t^n by at most
// the top cell's half-width error 1 - (1 - 1/(2N))^n (t^n is convex and monotone for n >= 1, so
// the steepest cell is the top one); entry rounding adds 2^-(B+1); output truncation 2^-16; the
// series quantization (2^-28 on t) adds n * 2^-28.
TEST(ExponentLut, PerExponentTableWithinDerivedBound) {
  for (int a : {6, 10}) {
    for (double n : {1.0, 2.0, 2.5, 16.0, 1000.0}) {
      UnitConfig cfg;
      cfg.specular.kind = SpecularUnitKind::kLut;
      cfg.specular.lut.addr_bits = a;
      cfg.specular.lut.entry_bits = 16;
      const double nn = std::ldexp(1.0, a);
      const double bound = 1.0 - std::pow(1.0 - 1.0 / (2 * nn), n) + std::ldexp(1.0, -17) +
                           std::ldexp(1.0, -16) + n * std::ldexp(1.0, -28);
      // measure_unit's absolute error is in 8-bit LSBs.
      const SpecErrors e = measure_unit(cfg, n, 2048);
      EXPECT_LE(e.abs_lsb / 256.0, bound) << "A " << a << " n " << n;
      // ... and the bound is not vacuous: the top cell really costs most of it.
      EXPECT_GE(e.abs_lsb / 256.0, 0.5 * (1.0 - std::pow(1.0 - 1.0 / (2 * nn), n)) - 1e-4);
    }
  }
}

TEST(ExponentLut, IndexAtBothEndsAndBeyond) {
  UnitConfig cfg;
  cfg.specular.kind = SpecularUnitKind::kLut;
  cfg.specular.lut.addr_bits = 4;
  cfg.specular.lut.entry_bits = 8;
  for (LutIndex rule : {LutIndex::kTruncate, LutIndex::kNearest}) {
    cfg.specular.lut.index = rule;
    SpecularUnit unit(cfg);
    TableCmd t;
    for (int i = 0; i < 16; ++i) t.entries.push_back(10 * i + 1);  // entry value names its address
    unit.load_table(t);
    MaterialCmd m;
    m.exponent = 1 << kExponentFracBits;
    m.unit_params = plan_specular(cfg, 1.0).unit_params;
    unit.load_material(m);
    const auto affine = plan_specular(cfg, 1.0).affine[0];
    auto entry_at = [&](double tv) {
      const int64_t s = cfg.series.from_double(affine.first * tv + affine.second);
      return cfg.specular.out.to_double(unit.evaluate(&s)) * 256.0;
    };
    EXPECT_EQ(entry_at(0.0), 1.0);
    EXPECT_EQ(entry_at(-0.3), 1.0);
    EXPECT_EQ(entry_at(1.0), 151.0);
    EXPECT_EQ(entry_at(1.2), 151.0);
    EXPECT_EQ(entry_at(0.999), 151.0);
  }
}

TEST(ExponentLut, InterpolationReachesLastEntryAtOne) {
  UnitConfig cfg;
  cfg.specular.kind = SpecularUnitKind::kLut;
  cfg.specular.lut.addr_bits = 2;  // smallest table that interpolates
  cfg.specular.lut.entry_bits = 4;
  cfg.specular.lut.interp_bits = 2;
  SpecularUnit unit(cfg);
  TableCmd t;
  t.entries = {0, 4, 8, 15};
  unit.load_table(t);
  const auto affine = plan_specular(cfg, 1.0).affine[0];
  auto at = [&](double tv) {
    const int64_t s = cfg.series.from_double(affine.first * tv + affine.second);
    return cfg.specular.out.to_double(unit.evaluate(&s)) * 16.0;
  };
  EXPECT_EQ(at(1.0), 15.0);
  EXPECT_EQ(at(2.0), 15.0);  // saturated address: pair (e3, e3)
  EXPECT_EQ(at(0.0), 0.0);
  EXPECT_EQ(at(0.5), 6.0);  // address 1.5: halfway between 4 and 8
}

TEST(ExponentLut, RejectsBadTableCommands) {
  LutConfig c;
  c.addr_bits = 3;
  c.entry_bits = 4;
  const FixedFormat series{32, 4, true, Quantization::kTruncate, Overflow::kWrap};
  ExponentLut lut(c, series, kOut);
  TableCmd big;
  big.entries = {16};
  EXPECT_THROW(lut.load_table(big), std::invalid_argument);
  TableCmd past;
  past.base = 7;
  past.entries = {1, 2};
  EXPECT_THROW(lut.load_table(past), std::invalid_argument);
  EXPECT_THROW(lut.load_params({29}), std::invalid_argument);
}

// Two material banks (command_stream.h, TABLE): a MATERIAL switches bank, a per-material TABLE
// writes the current bank's table only, any other TABLE both; a pixel reads the current one.
TEST(ExponentLut, TwoBanksKeepAPerMaterialTableEach) {
  LutConfig c;
  c.addr_bits = 2;
  c.entry_bits = 4;
  const FixedFormat series{32, 4, true, Quantization::kTruncate, Overflow::kWrap};
  const FixedFormat out{4, 0, false, Quantization::kTruncate, Overflow::kSaturate};  // u0.4
  ExponentLut lut(c, series, out, 2);
  lut.load_table(TableCmd{0, {1, 2, 3, 4}, false});
  EXPECT_EQ(lut.table(), (std::vector<int64_t>{1, 2, 3, 4}));
  lut.next_material();  // bank 1 got the shared entries too
  EXPECT_EQ(lut.table(), (std::vector<int64_t>{1, 2, 3, 4}));
  lut.load_table(TableCmd{1, {9, 10}, true});
  EXPECT_EQ(lut.table(), (std::vector<int64_t>{1, 9, 10, 4}));
  // t = 0.25 + 1/64 addresses entry 1 (truncate, 4 entries, shift 0): 9/16 in bank 1.
  const int64_t x = series.from_double(0.25 + 1.0 / 64);
  EXPECT_EQ(lut.evaluate(x), 9);
  lut.next_material();  // back to bank 0: untouched by the per-material TABLE
  EXPECT_EQ(lut.table(), (std::vector<int64_t>{1, 2, 3, 4}));
  EXPECT_EQ(lut.evaluate(x), 2);
  // One bank: the bit changes nothing.
  ExponentLut one(c, series, out);
  one.load_table(TableCmd{0, {1, 2, 3, 4}, true});
  one.next_material();
  EXPECT_EQ(one.table(), (std::vector<int64_t>{1, 2, 3, 4}));
  EXPECT_THROW(ExponentLut(c, series, out, 3), std::invalid_argument);
}

TEST(ExponentLut, HexFileHoldsTheTable) {
  LutConfig c;
  c.addr_bits = 5;
  c.entry_bits = 10;
  const FixedFormat series{32, 4, true, Quantization::kTruncate, Overflow::kWrap};
  ExponentLut lut(c, series, kOut);
  const auto entries = lut_entries(c, 7.0);
  lut.load_table(to_table_commands(entries)[0]);
  const std::string path = std::string(SHADESIM_BINARY_DIR) + "/exponent_lut_test.hex";
  lut.write_hex(path);
  std::ifstream is(path);
  std::string line;
  size_t i = 0;
  while (std::getline(is, line)) {
    ASSERT_LT(i, entries.size());
    EXPECT_EQ(line.size(), 3u);  // ceil(10 / 4) hex digits
    EXPECT_EQ(std::stoll(line, nullptr, 16), entries[i]) << "line " << i;
    ++i;
  }
  EXPECT_EQ(i, entries.size());
  std::remove(path.c_str());
  EXPECT_THROW(lut.write_hex("/nonexistent-dir/x.hex"), std::runtime_error);
}

TEST(ExponentLut, CostsAndReload) {
  LutConfig c;
  c.addr_bits = 10;
  c.entry_bits = 8;
  EXPECT_EQ(ExponentLut::table_bits(c), 8192);
  EXPECT_EQ(ExponentLut::reload_cycles(c), 1024);
  UnitConfig cfg;
  cfg.specular.kind = SpecularUnitKind::kLut;
  cfg.specular.lut = c;
  EXPECT_EQ(plan_specular(cfg, 20.0).load_cycles, 1024);
  c.addressing = LutAddressing::kShared;
  EXPECT_EQ(ExponentLut::reload_cycles(c), 0);
  cfg.specular.lut = c;
  EXPECT_TRUE(plan_specular(cfg, 20.0).tables.empty());
  EXPECT_EQ(shared_lut_tables(cfg).size(), 1u);
}

// The shared exp table: error independent of n for large n, bounded by the first-order
// mismatch exp(-n(1-t)) vs t^n (relative 1 - exp(-n s^2/2) at the epicentre edge) plus half a
// table step of exp (U/(2(N-1)) relative) plus entry rounding.
TEST(ExponentLut, SharedExpTableEpicentreBound) {
  UnitConfig cfg;
  cfg.specular.kind = SpecularUnitKind::kLut;
  cfg.specular.lut.addressing = LutAddressing::kShared;
  cfg.specular.lut.index = LutIndex::kNearest;
  cfg.specular.lut.addr_bits = 12;
  cfg.specular.lut.entry_bits = 16;
  for (double n : {64.0, 1000.0}) {
    const double s = 1.0 - std::pow(0.5, 1.0 / n);
    const double bound =
        (std::exp(n * (s + s * s / 2 + s * s * s / 2)) - std::exp(n * s)) / std::exp(n * s) +
        16.0 / (2 * 4095) * 1.01 + std::ldexp(1.0, -14);
    EXPECT_LE(measure_unit(cfg, n, 1024).epi_rel, bound) << "n " << n;
  }
}

}  // namespace
}  // namespace shadesim
