// rtl/specular_unit.sv against SpecularUnit: the cfg-port mapping of MATERIAL words (exponent at
// index 0 resets the unit parameters, unit_params[i] at index 1 + i) and TABLE entries
// (base + i), the series order (schlick: numerator low, denominator high), the timing contract
// (LATENCY, busy_o / INTERVAL) and ideal's constant 0.
#include <gtest/gtest.h>

#include "model/specular_unit.h"
#include "tests/rtl_units/rtl_unit_driver.h"

namespace shadesim {
namespace rtl_units {
namespace {

UnitConfig slot_config(const Params& p) {
  UnitConfig u;
  u.series = series_format(p);
  u.specular = unit_fields(p, static_cast<SpecularUnitKind>(get(p, "SPECULAR_KIND")));
  u.specular.out = out_format(p, "SPECULAR_OUT_");
  return u;
}

// The model's declared timing for the selected unit.
int latency_of(const SpecularConfig& s) {
  switch (s.kind) {
    case SpecularUnitKind::kLut:
      return ExponentLut::latency(s.lut);
    case SpecularUnitKind::kSchlick:
      return SchlickDivider::latency(s.schlick);
    case SpecularUnitKind::kWpow:
      return WpowUnit::latency(s.wpow);
    case SpecularUnitKind::kIdeal:
    default:
      return 0;
  }
}
int interval_of(const SpecularConfig& s) {
  switch (s.kind) {
    case SpecularUnitKind::kSchlick:
      return SchlickDivider::cycles_per_pixel(s.schlick);
    case SpecularUnitKind::kWpow:
      return WpowUnit::cycles_per_pixel(s.wpow);
    default:
      return 1;
  }
}

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

// A material as the shade unit forwards it: exponent, then unit_params; then its TABLE
// commands (the per-exponent reload), split into two commands at a random base.
template <class V>
void load_material(V& dut, SpecularUnit& model, const UnitConfig& u, std::mt19937_64& rng,
                   int round) {
  MaterialCmd m;
  m.ambient.assign(1, 0);
  m.spec_colour.assign(1, 0);
  m.exponent = static_cast<int64_t>(10 + round) << kExponentFracBits;
  const int fs = u.series.frac_bits();
  const bool defaults = round % 3 == 2;  // empty unit_params after a non-default material
  if (u.specular.kind == SpecularUnitKind::kLut && !defaults) {
    m.unit_params = {static_cast<int64_t>(rng() % static_cast<uint64_t>(fs + 1))};
  } else if (u.specular.kind == SpecularUnitKind::kWpow && !defaults) {
    const int k = WpowUnit::stages(u.specular.wpow);
    m.unit_params = {static_cast<int64_t>(rng() % static_cast<uint64_t>(fs + 1)),
                     static_cast<int64_t>(rng() % static_cast<uint64_t>(k + 1))};
  }
  model.load_material(m);
  send_cfg(dut, false, 0, m.exponent);
  for (size_t i = 0; i < m.unit_params.size(); ++i) {
    send_cfg(dut, false, static_cast<uint32_t>(1 + i), m.unit_params[i]);
  }
  if (u.specular.kind != SpecularUnitKind::kLut) return;
  const int entries = 1 << u.specular.lut.addr_bits;
  const auto split = static_cast<uint32_t>(rng() % static_cast<uint64_t>(entries));
  const int64_t top = int64_t{1} << u.specular.lut.entry_bits;
  TableCmd lo, hi;
  lo.base = 0;
  hi.base = split;
  for (int i = 0; i < entries; ++i) {
    (static_cast<uint32_t>(i) < split ? lo : hi)
        .entries.push_back(static_cast<int64_t>(rng() % static_cast<uint64_t>(top)));
  }
  // Load the high part first: the base must be honoured, not the arrival order.
  for (const TableCmd* t : {&hi, &lo}) {
    model.load_table(*t);
    for (size_t i = 0; i < t->entries.size(); ++i) {
      send_cfg(dut, true, static_cast<uint32_t>(t->base + i), t->entries[i]);
    }
  }
}

template <class V>
void check_slot(const std::string& name) {
  const Params p = config_params(name);
  const UnitConfig u = slot_config(p);
  const FixedFormat& series = u.series;
  const int spl = u.specular.series_per_light();
  ASSERT_EQ(spl, get(p, "SERIES_PER_LIGHT"));
  SpecularUnit model(u);
  std::mt19937_64 rng(static_cast<uint64_t>(name.size()) * 31u);
  V dut;
  reset(dut);
  const int latency = latency_of(u.specular);
  const int interval = interval_of(u.specular);

  const std::vector<int64_t> hard = hard_series(series);
  const int64_t one = int64_t{1} << series.frac_bits();
  std::uniform_int_distribution<int64_t> near(-one / 8, one + one / 8);
  std::uniform_int_distribution<int64_t> any(series.raw_min(), series.raw_max());
  for (int round = 0; round < 6; ++round) {
    load_material(dut, model, u, rng, round);
    std::vector<std::vector<int64_t>> inputs;
    for (int64_t h : hard)
      for (int64_t h2 : {h, one, one / 2, int64_t{1}}) inputs.push_back({h, h2});
    for (int i = 0; i < 3000; ++i)
      inputs.push_back({near(rng), i % 4 ? near(rng) + one / 2 : any(rng)});
    Mismatch mm;
    UnitRun<V> run{dut, latency, rng};
    run.set_input = [&](int64_t k) {
      uint64_t bits = 0;
      for (int s = 0; s < spl; ++s) {
        const int64_t raw = k >= 0 ? inputs[static_cast<size_t>(k)][static_cast<size_t>(s)]
                                   : static_cast<int64_t>(rng());
        bits |= to_bits(raw, series.wl) << (s * series.wl);
      }
      dut.series_i = bits;
    };
    run.expected = [&](int64_t k) { return model.evaluate(inputs[static_cast<size_t>(k)].data()); };
    run.describe = [&](int64_t k) {
      return name + " material " + std::to_string(round) + " series " +
             std::to_string(inputs[static_cast<size_t>(k)][0]) + " / " +
             std::to_string(inputs[static_cast<size_t>(k)][1]);
    };
    run.busy = [&] { return dut.busy_o != 0; };
    run.mismatch = &mm;
    const auto n = static_cast<int64_t>(inputs.size());
    if (latency == 0) {
      // ideal: combinational 0, whatever the series.
      for (int64_t k = 0; k < n; ++k) {
        run.set_input(k);
        dut.en_i = rng() & 1;
        dut.eval();
        if (dut.spec_o != 0 || dut.busy_o != 0) mm.add("ideal slot output not 0");
        clock_edge(dut);
      }
    } else if (interval == 1) {
      run.pipelined(n, 80);
    } else {
      ASSERT_EQ(interval, latency);
      run.iterative(n);
    }
    EXPECT_EQ(mm.count, 0) << name << " material " << round << ": first mismatch " << mm.first;
  }
}

TEST(SpecularSlotRtl, LutInterpolatedCfgMapping) { check_slot<Vslot_lut>("slot_lut"); }
TEST(SpecularSlotRtl, SchlickIterativeSeriesOrderAndBusy) {
  check_slot<Vslot_schlick>("slot_schlick");
}
TEST(SpecularSlotRtl, WpowIterativeParamsAndBusy) { check_slot<Vslot_wpow>("slot_wpow"); }
TEST(SpecularSlotRtl, IdealIsZero) { check_slot<Vslot_ideal>("slot_ideal"); }

}  // namespace
}  // namespace rtl_units
}  // namespace shadesim
