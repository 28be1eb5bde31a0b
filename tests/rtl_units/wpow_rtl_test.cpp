// rtl/wpow_unit.sv against WpowUnit: every output bit, latency K square_stages + 1, II 1
// (pipelined) or K + 1 (iterative), over every shift and squaring count; exhaustive series values
// at small widths, hard cases (base 0 and just below/above, 1, > 1, < 0) plus random at real
// widths.
#include <gtest/gtest.h>

#include "model/command_stream.h"
#include "model/wpow_unit.h"
#include "tests/rtl_units/rtl_unit_driver.h"

namespace shadesim {
namespace rtl_units {
namespace {

WpowConfig wpow_config(const Params& p) { return unit_fields(p, SpecularUnitKind::kWpow).wpow; }

template <class V>
void send_param(V& dut, uint32_t addr, int64_t data) {
  dut.en_i = 0;
  dut.cfg_valid_i = 1;
  dut.cfg_table_i = 0;
  dut.cfg_addr_i = addr;
  dut.cfg_data_i = static_cast<uint64_t>(data);
  dut.eval();
  clock_edge(dut);
  dut.cfg_valid_i = 0;
}

// Series values whose base (series << shift, B fraction bits) lands on 0, 1 and their
// neighbours, for this shift; then the generic hard cases and random values near [0, 1].
std::vector<int64_t> wpow_inputs(const FixedFormat& f, int shift, int base_bits,
                                 std::mt19937_64& rng, int n_random) {
  std::vector<int64_t> v = hard_series(f);
  const int src = f.frac_bits() - shift;  // fraction bits of the shifted series
  const int64_t lsb = src > base_bits ? int64_t{1} << (src - base_bits) : 1;
  const int64_t one = src >= 0 && src < 62 ? int64_t{1} << src : 0;
  for (int64_t centre : {int64_t{0}, one, lsb, one - lsb})
    for (int64_t d : {-lsb - 1, -lsb, int64_t{-1}, int64_t{0}, int64_t{1}, lsb - 1, lsb, lsb + 1}) {
      const int64_t x = centre + d;
      if (x >= f.raw_min() && x <= f.raw_max()) v.push_back(x);
    }
  std::uniform_int_distribution<int64_t> any(f.raw_min(), f.raw_max());
  const int64_t hi = std::min<int64_t>(f.raw_max(), one + one / 8);
  std::uniform_int_distribution<int64_t> near(std::max<int64_t>(f.raw_min(), -one / 8), hi);
  for (int i = 0; i < n_random; ++i) v.push_back(i % 5 == 0 ? any(rng) : near(rng));
  return v;
}

template <class V>
void check_wpow(const std::string& name, bool exhaustive, int n_random) {
  const Params p = config_params(name);
  const WpowConfig c = wpow_config(p);
  const FixedFormat series = series_format(p);
  const FixedFormat out = out_format(p, "OUT_");
  const int k_stages = WpowUnit::stages(c);
  WpowUnit model(c, series, out);
  std::mt19937_64 rng(static_cast<uint64_t>(name.size()) * 7919u);
  V dut;
  reset(dut);
  std::vector<int64_t> all;
  if (exhaustive)
    for (int64_t x = series.raw_min(); x <= series.raw_max(); ++x) all.push_back(x);

  // Every squaring count with a few shifts (every shift when exhaustive), then empty
  // unit_params (defaults shift 0, s = K) after a non-default material.
  struct Material {
    int shift, squarings;
    bool defaults;
  };
  std::vector<Material> materials;
  for (int s = 0; s <= k_stages; ++s)
    for (int shift = 0; shift <= series.frac_bits(); ++shift)
      if (exhaustive || shift == 0 || shift == 2 || shift == series.frac_bits() || shift == s + 3)
        materials.push_back({shift, s, false});
  materials.push_back({0, k_stages, true});

  for (const Material& m : materials) {
    send_param(dut, 0, int64_t{40} << kExponentFracBits);
    if (m.defaults) {
      model.load_params({});
    } else {
      send_param(dut, 1, m.shift);
      send_param(dut, 2, m.squarings);
      model.load_params({m.shift, m.squarings});
    }
    const std::vector<int64_t> inputs =
        exhaustive ? all : wpow_inputs(series, m.shift, c.base_bits, rng, n_random);
    Mismatch mm;
    UnitRun<V> run{dut, WpowUnit::latency(c), rng};
    run.set_input = [&](int64_t k) {
      const int64_t raw = k >= 0 ? inputs[static_cast<size_t>(k)] : static_cast<int64_t>(rng());
      dut.series_i = to_bits(raw, series.wl);
    };
    run.expected = [&](int64_t k) { return model.evaluate(inputs[static_cast<size_t>(k)]); };
    run.describe = [&](int64_t k) {
      return name + " series " + std::to_string(inputs[static_cast<size_t>(k)]) + " shift " +
             std::to_string(m.shift) + " squarings " + std::to_string(m.squarings);
    };
    run.busy = [&] { return dut.busy_o != 0; };
    run.mismatch = &mm;
    const auto n = static_cast<int64_t>(inputs.size());
    if (WpowUnit::cycles_per_pixel(c) == 1) {
      run.pipelined(n, 85);
    } else {
      ASSERT_EQ(WpowUnit::cycles_per_pixel(c), WpowUnit::latency(c));
      run.iterative(n);
    }
    EXPECT_EQ(mm.count, 0) << name << " shift " << m.shift << " squarings " << m.squarings
                           << (m.defaults ? " (empty unit_params)" : "") << ": first mismatch "
                           << mm.first;
  }
}

// The squarer on every base it can be given: with B = 16, a series of 16 fraction bits and
// shift 0, the base is the series value itself, so series 0 .. 2^16 (b <= 2^B) feeds every
// possible base to one squaring, whose truncated square the 17-bit output holds unchanged. The
// RTL sums a square's partial products (each cross term once, doubled), or with square_stages 2
// two partial squares and a cross product a cycle apart; the model multiplies.
template <class V>
void check_every_square(const std::string& name, int square_stages) {
  const Params p = config_params(name);
  const WpowConfig c = wpow_config(p);
  const FixedFormat series = series_format(p);
  const FixedFormat out = out_format(p, "OUT_");
  ASSERT_EQ(c.base_bits, 16);
  ASSERT_EQ(c.square_stages, square_stages);
  ASSERT_EQ(WpowUnit::latency(c), square_stages + 1);
  ASSERT_EQ(series.frac_bits(), 16);
  ASSERT_EQ(out.frac_bits(), 16);
  WpowUnit model(c, series, out);
  std::mt19937_64 rng(2);
  V dut;
  reset(dut);
  send_param(dut, 0, int64_t{40} << kExponentFracBits);
  send_param(dut, 1, 0);
  send_param(dut, 2, 1);
  model.load_params({0, 1});
  std::vector<int64_t> inputs;
  for (int64_t b = 0; b <= (int64_t{1} << 16); ++b) inputs.push_back(b);
  Mismatch mm;
  UnitRun<V> run{dut, WpowUnit::latency(c), rng};
  run.set_input = [&](int64_t k) {
    const int64_t raw = k >= 0 ? inputs[static_cast<size_t>(k)] : static_cast<int64_t>(rng());
    dut.series_i = to_bits(raw, series.wl);
  };
  run.expected = [&](int64_t k) { return model.evaluate(inputs[static_cast<size_t>(k)]); };
  run.describe = [&](int64_t k) {
    return name + " base " + std::to_string(inputs[static_cast<size_t>(k)]);
  };
  run.busy = [&] { return dut.busy_o != 0; };
  run.mismatch = &mm;
  run.pipelined(static_cast<int64_t>(inputs.size()), 85);
  EXPECT_EQ(mm.count, 0) << "first mismatch " << mm.first;
  // The model's square is the exact product truncated: spot-check it against integers.
  for (int64_t b :
       {int64_t{0}, int64_t{1}, int64_t{255}, int64_t{46341}, int64_t{65535}, int64_t{65536}}) {
    EXPECT_EQ(model.evaluate(b), (b * b) >> 16) << b;
  }
}

TEST(WpowUnitRtl, M2Base16EverySquareEqualsTheModelsProduct) {
  check_every_square<Vwpow_m2_b16>("wpow_m2_b16", 1);
}
TEST(WpowUnitRtl, M2Base16SplitSquareEverySquareEqualsTheModelsProduct) {
  check_every_square<Vwpow_m2_b16_sq2>("wpow_m2_b16_sq2", 2);
}

TEST(WpowUnitRtl, M4SmallestPipelinedExhaustive) {
  check_wpow<Vwpow_small_pipe>("wpow_small_pipe", true, 0);
}
TEST(WpowUnitRtl, M4SmallestIterativeExhaustive) {
  check_wpow<Vwpow_small_iter>("wpow_small_iter", true, 0);
}
TEST(WpowUnitRtl, M1NoSquarerExhaustive) { check_wpow<Vwpow_m1>("wpow_m1", true, 0); }
TEST(WpowUnitRtl, W16PipelinedHardAndRandom) { check_wpow<Vwpow_w16>("wpow_w16", false, 4000); }
TEST(WpowUnitRtl, M32IterativeRoundedOutputHardAndRandom) {
  check_wpow<Vwpow_m32_iter>("wpow_m32_iter", false, 2000);
}
// Split squarings: latency 2K + 1, one pixel per cycle.
TEST(WpowUnitRtl, M4SplitSquaresExhaustive) {
  check_wpow<Vwpow_small_sq2>("wpow_small_sq2", true, 0);
}
TEST(WpowUnitRtl, M4OddBaseSplitSquaresRoundedOutputExhaustive) {
  check_wpow<Vwpow_small_b5_sq2>("wpow_small_b5_sq2", true, 0);
}
TEST(WpowUnitRtl, W16SplitSquaresHardAndRandom) {
  check_wpow<Vwpow_w16_sq2>("wpow_w16_sq2", false, 4000);
}

}  // namespace
}  // namespace rtl_units
}  // namespace shadesim
