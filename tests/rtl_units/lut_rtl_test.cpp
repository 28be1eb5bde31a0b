// rtl/exponent_lut.sv against ExponentLut: every output bit, latency 2 (3 with interpolation),
// tables loaded through the cfg port (TABLE words) and from a $readmemh file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "model/exponent_lut.h"
#include "tests/rtl_units/rtl_unit_driver.h"

namespace shadesim {
namespace rtl_units {
namespace {

LutConfig lut_config(const Params& p) { return unit_fields(p, SpecularUnitKind::kLut).lut; }

template <class V>
void send_cfg(V& dut, bool table, uint32_t addr, int64_t data) {
  dut.en_i = 0;
  dut.cfg_valid_i = 1;
  dut.cfg_table_i = table;
  dut.cfg_addr_i = addr;
  dut.cfg_data_i = static_cast<uint64_t>(data);
  dut.eval();
  clock_edge(dut);
  dut.cfg_valid_i = 0;
}

// A random table with both extremes present, loaded into model and RTL by TABLE words.
template <class V>
void load_random_table(V& dut, ExponentLut& model, const LutConfig& c, std::mt19937_64& rng) {
  TableCmd t;
  t.base = 0;
  const int64_t top = (int64_t{1} << c.entry_bits) - 1;
  for (int i = 0; i < (1 << c.addr_bits); ++i) {
    t.entries.push_back(static_cast<int64_t>(rng() % static_cast<uint64_t>(top + 1)));
  }
  t.entries.front() = top;
  t.entries.back() = 0;
  model.load_table(t);
  for (size_t i = 0; i < t.entries.size(); ++i)
    send_cfg(dut, true, static_cast<uint32_t>(i), t.entries[i]);
}

// Runs one material: exponent word (resets shift), optionally a shift word, then the inputs.
template <class V>
Mismatch run_material(V& dut, ExponentLut& model, const FixedFormat& series, int shift,
                      bool send_shift, const std::vector<int64_t>& inputs, std::mt19937_64& rng,
                      int latency, int en_pct) {
  send_cfg(dut, false, 0, int64_t{8} << kExponentFracBits);
  if (send_shift) {
    send_cfg(dut, false, 1, shift);
    model.load_params({shift});
  } else {
    model.load_params({});
  }
  Mismatch mm;
  UnitRun<V> run{dut, latency, rng};
  run.set_input = [&](int64_t k) {
    const int64_t raw = k >= 0 ? inputs[static_cast<size_t>(k)] : static_cast<int64_t>(rng());
    dut.series_i = to_bits(raw, series.wl);
  };
  run.expected = [&](int64_t k) { return model.evaluate(inputs[static_cast<size_t>(k)]); };
  run.describe = [&](int64_t k) {
    return "series " + std::to_string(inputs[static_cast<size_t>(k)]) + " shift " +
           std::to_string(send_shift ? shift : 0);
  };
  run.mismatch = &mm;
  run.pipelined(static_cast<int64_t>(inputs.size()), en_pct);
  return mm;
}

std::vector<int64_t> all_values(const FixedFormat& f) {
  std::vector<int64_t> v;
  for (int64_t x = f.raw_min(); x <= f.raw_max(); ++x) v.push_back(x);
  return v;
}

std::vector<int64_t> random_values(const FixedFormat& f, std::mt19937_64& rng, int n) {
  std::vector<int64_t> v = hard_series(f);
  std::uniform_int_distribution<int64_t> any(f.raw_min(), f.raw_max());
  // Mostly t in [-0.25, 1.25] at the largest shift that keeps it in range, the rest anywhere.
  const int64_t one = int64_t{1} << f.frac_bits();
  std::uniform_int_distribution<int64_t> near(-one / 4, one + one / 4);
  for (int i = 0; i < n; ++i) v.push_back(i % 4 == 0 ? any(rng) : near(rng));
  return v;
}

template <class V>
void exhaustive_lut(const std::string& name) {
  const Params p = config_params(name);
  const LutConfig c = lut_config(p);
  const FixedFormat series = series_format(p);
  const FixedFormat out = out_format(p, "OUT_");
  ExponentLut model(c, series, out);
  ASSERT_EQ(ExponentLut::latency(c), c.interp_bits > 0 ? 3 : 2);
  std::mt19937_64 rng(11);
  V dut;
  reset(dut);
  load_random_table(dut, model, c, rng);
  const std::vector<int64_t> inputs = all_values(series);
  // Every series value at every shift; the last material sends no shift word (default 0 after
  // a shifted material: the exponent word must reset it).
  for (int shift = 0; shift <= series.frac_bits(); ++shift) {
    const Mismatch mm = run_material(dut, model, series, shift, true, inputs, rng,
                                     ExponentLut::latency(c), shift % 2 ? 100 : 70);
    EXPECT_EQ(mm.count, 0) << name << " shift " << shift << ": first mismatch " << mm.first;
  }
  const Mismatch mm =
      run_material(dut, model, series, 0, false, inputs, rng, ExponentLut::latency(c), 80);
  EXPECT_EQ(mm.count, 0) << name << " default shift: first mismatch " << mm.first;
  // A second table (a material switch), loaded over the first.
  load_random_table(dut, model, c, rng);
  const Mismatch mm2 =
      run_material(dut, model, series, 1, true, inputs, rng, ExponentLut::latency(c), 90);
  EXPECT_EQ(mm2.count, 0) << name << " second table: first mismatch " << mm2.first;
}

TEST(ExponentLutRtl, SmallestWidthsExhaustiveEveryShift) {
  exhaustive_lut<Vlut_small>("lut_small");
}

TEST(ExponentLutRtl, InterpolationNearestRoundedOutputExhaustive) {
  exhaustive_lut<Vlut_interp>("lut_interp");
}

TEST(ExponentLutRtl, TableFromReadmemhFileThenTableCommands) {
  const Params p = config_params("lut_file");
  const LutConfig c = lut_config(p);
  const FixedFormat series = series_format(p);
  const FixedFormat out = out_format(p, "OUT_");
  ExponentLut model(c, series, out);
  std::mt19937_64 rng(5);
  TableCmd t;
  for (int i = 0; i < model.entries(); ++i) t.entries.push_back(static_cast<int64_t>(rng() % 256));
  t.entries.back() = 255;
  model.load_table(t);
  model.write_hex(SHADESIM_RTL_UNITS_TABLE_FILE);

  Vlut_file dut;  // the initial block reads the file on the first eval
  reset(dut);
  std::remove(SHADESIM_RTL_UNITS_TABLE_FILE);
  const std::vector<int64_t> inputs = random_values(series, rng, 20000);
  for (int shift : {0, 3, series.frac_bits()}) {
    const Mismatch mm =
        run_material(dut, model, series, shift, true, inputs, rng, ExponentLut::latency(c), 75);
    EXPECT_EQ(mm.count, 0) << "file table, shift " << shift << ": first mismatch " << mm.first;
  }
  // A per-exponent reload over the file's contents, then entries at both ends only.
  load_random_table(dut, model, c, rng);
  TableCmd ends;
  ends.base = 0;
  ends.entries = {17};
  model.load_table(ends);
  send_cfg(dut, true, 0, 17);
  ends.base = static_cast<uint32_t>(model.entries() - 1);
  ends.entries = {254};
  model.load_table(ends);
  send_cfg(dut, true, ends.base, 254);
  // An address past the table is ignored by the RTL (the model rejects it).
  send_cfg(dut, true, static_cast<uint32_t>(model.entries()), 3);
  const Mismatch mm =
      run_material(dut, model, series, 2, true, inputs, rng, ExponentLut::latency(c), 100);
  EXPECT_EQ(mm.count, 0) << "reloaded table: first mismatch " << mm.first;
}

TEST(ExponentLutRtlDeathTest, MissingTableFileIsFatal) {
  ::testing::FLAGS_gtest_death_test_style = "threadsafe";
  std::remove(SHADESIM_RTL_UNITS_TABLE_FILE);
  EXPECT_DEATH(
      {
        // Verilator prints $fatal's message on stdout: send it where the death test looks.
        std::fflush(stdout);
        dup2(STDERR_FILENO, STDOUT_FILENO);
        Vlut_file dut;
        reset(dut);
      },
      "cannot open TABLE_FILE");
}

}  // namespace
}  // namespace rtl_units
}  // namespace shadesim
