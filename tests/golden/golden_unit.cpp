#include "tests/golden/golden_unit.h"

#define SC_INCLUDE_FX
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <systemc>

namespace shadesim::golden {
namespace {

using Int128 = __int128;

sc_dt::sc_q_mode q_mode(Quantization q) {
  return q == Quantization::kTruncate ? sc_dt::SC_TRN : sc_dt::SC_RND;
}
sc_dt::sc_o_mode o_mode(Overflow o) {
  return o == Overflow::kSaturate ? sc_dt::SC_SAT : sc_dt::SC_WRAP;
}

sc_dt::sc_fxval exact_value(Int128 raw, int src_frac) {
  sc_dt::sc_bigint<128> big;
  big.range(127, 64) = static_cast<int64_t>(raw >> 64);
  big.range(63, 0) = static_cast<uint64_t>(raw);
  const sc_dt::sc_fxval value(big);
  return src_frac >= 0 ? sc_dt::sc_fxval(value >> src_frac) : sc_dt::sc_fxval(value << -src_frac);
}

// The raw integer of a quantized number: its value times 2^frac_bits, read by SystemC (an
// sc_fxval holds it exactly; no bit manipulation of our own).
template <typename Fx>
int64_t raw_of(const Fx& fx, const FixedFormat& format) {
  return (sc_dt::sc_fxval(fx) << format.frac_bits()).to_int64();
}

template <typename Value>
int64_t convert(const Value& value, const FixedFormat& f) {
  if (f.is_signed) {
    sc_dt::sc_fix fx(f.wl, f.iwl, q_mode(f.quant), o_mode(f.overflow));
    fx = value;
    return raw_of(fx, f);
  }
  sc_dt::sc_ufix fx(f.wl, f.iwl, q_mode(f.quant), o_mode(f.overflow));
  fx = value;
  return raw_of(fx, f);
}

FixedFormat unsigned_format(int wl, int iwl, Quantization q) {
  FixedFormat f;
  f.wl = wl;
  f.iwl = iwl;
  f.is_signed = false;
  f.quant = q;
  f.overflow = Overflow::kSaturate;
  return f;
}

// The quadratic of model/command_stream.h (TRIANGLE), exactly, in coef raw units.
Int128 quadratic(const int64_t* t, Int128 dx, Int128 dy) {
  return Int128{t[0]} + t[1] * dy + t[2] * dx + t[3] * dy * dy + t[4] * dx * dy + t[5] * dx * dx;
}

// State of the unit between commands, as the command stream's documentation defines it.
struct State {
  std::vector<int64_t> ambient, spec_colour, diffuse_colour, unit_params;
  uint32_t gate_only = 0;  // MATERIAL header: lights whose diffuse series only gates specular
  double exponent = 0;
  // The LUT's tables, one per material bank (command_stream.h, TABLE): each MATERIAL switches
  // bank; a per-material TABLE writes the current bank's, any other TABLE every bank's.
  std::vector<std::vector<int64_t>> tables;
  size_t bank = 0;
  TriangleCmd triangle;
  bool have_material = false, have_triangle = false;
};

// Specular intensity of one light in the specular out format, from the unit's header comment.
int64_t specular(const UnitConfig& c, const State& st, const int64_t* series) {
  const SpecularConfig& s = c.specular;
  const int fs = c.series.frac_bits();
  switch (s.kind) {
    case SpecularUnitKind::kIdeal: {  // model/specular_ideal.h: pow of t clamped to [0, 1]
      const double t = std::clamp(std::ldexp(static_cast<double>(series[0]), -fs), 0.0, 1.0);
      return sc_quantize(std::pow(t, st.exponent), s.out);
    }
    case SpecularUnitKind::kWpow: {  // model/wpow_unit.h
      int stages = 0;
      while ((1 << stages) < s.wpow.max_m) ++stages;
      const int shift = st.unit_params.empty() ? 0 : static_cast<int>(st.unit_params[0]);
      const int squarings = st.unit_params.empty() ? stages : static_cast<int>(st.unit_params[1]);
      const int b_frac = s.wpow.base_bits;
      const FixedFormat base = unsigned_format(b_frac + 1, 1, Quantization::kTruncate);
      int64_t b = sc_quantize(series[0], fs - shift, base);  // x * 2^shift, into u1.B
      b = std::min(b, int64_t{1} << b_frac);                 // clamp to 1
      for (int k = 0; k < squarings; ++k) b = sc_quantize(Int128{b} * b, 2 * b_frac, base);
      return sc_quantize(b, b_frac, s.out);
    }
    case SpecularUnitKind::kSchlick: {  // model/schlick_divider.h
      const int64_t num = series[0], den = series[1];
      if (num <= 0) return 0;
      if (den <= 0) return sc_quantize(1, 0, s.out);
      const FixedFormat operand =
          unsigned_format(s.schlick.operand_bits + 2, 2, Quantization::kTruncate);
      const int64_t n = sc_quantize(num, fs, operand), d = sc_quantize(den, fs, operand);
      if (n == 0) return 0;
      if (n >= d) return sc_quantize(1, 0, s.out);
      // Restoring division of Q steps from r = n < d gives floor(n 2^Q / d).
      const Int128 q = (Int128{n} << s.schlick.quotient_bits) / d;
      return sc_quantize(q, s.schlick.quotient_bits, s.out);
    }
    case SpecularUnitKind::kNone:  // no unit: shade() adds no specular term
      return 0;
    case SpecularUnitKind::kLut: {  // model/exponent_lut.h
      const LutConfig& l = s.lut;
      const int shift = st.unit_params.empty() ? 0 : static_cast<int>(st.unit_params[0]);
      const FixedFormat address = unsigned_format(
          l.addr_bits + l.interp_bits, l.addr_bits,
          l.index == LutIndex::kTruncate ? Quantization::kTruncate : Quantization::kRoundNearest);
      // The series x * 2^shift read as A.F: x's bits below the point moved up by A (+ shift).
      const int64_t a = sc_quantize(series[0], fs - shift - l.addr_bits, address);
      const int64_t idx = a >> l.interp_bits;
      const int64_t e0 = st.tables[st.bank].at(static_cast<size_t>(idx));
      if (l.interp_bits == 0) return sc_quantize(e0, l.entry_bits, s.out);
      const int64_t frac = a - (idx << l.interp_bits);
      const int64_t last = (int64_t{1} << l.addr_bits) - 1;
      const int64_t e1 = st.tables[st.bank].at(static_cast<size_t>(std::min(idx + 1, last)));
      const Int128 v = (Int128{e0} << l.interp_bits) + Int128{frac} * (e1 - e0);
      return sc_quantize(v, l.entry_bits + l.interp_bits, s.out);
    }
  }
  throw std::invalid_argument("golden: unknown specular unit kind");
}

}  // namespace

int64_t sc_quantize(Int128 raw, int src_frac, const FixedFormat& format) {
  return convert(exact_value(raw, src_frac), format);
}

int64_t sc_quantize(double value, const FixedFormat& format) {
  return convert(sc_dt::sc_fxval(value), format);
}

std::vector<Pixel> shade(const CommandStream& stream) {
  const UnitConfig& c = stream.config;
  const int series_count = c.series_per_triangle();
  const int per_light = c.specular.series_per_light();
  const int fs = c.series.frac_bits();
  const int fc = c.coef.frac_bits();
  const bool wrap = c.series.overflow == Overflow::kWrap;
  const FixedFormat out = [&] {
    FixedFormat f;  // u0.out_bits, round to nearest, saturating (model/pixel_combine.h)
    f.wl = c.out_bits;
    f.iwl = 0;
    f.is_signed = false;
    f.quant = Quantization::kRoundNearest;
    f.overflow = Overflow::kSaturate;
    return f;
  }();
  const int product_frac = c.specular.out.frac_bits() + c.spec_colour.frac_bits();

  State st;
  st.tables.assign(static_cast<size_t>(c.material_buffers),
                   std::vector<int64_t>(static_cast<size_t>(1) << c.specular.lut.addr_bits, 0));
  std::vector<Pixel> pixels;
  for (const Command& cmd : stream.commands) {
    if (const auto* m = std::get_if<MaterialCmd>(&cmd)) {
      st.ambient = m->ambient;
      st.spec_colour = m->spec_colour;
      st.diffuse_colour = m->diffuse_colour;
      st.unit_params = m->unit_params;
      st.gate_only = m->gate_only;
      st.exponent = static_cast<double>(m->exponent) / 65536.0;  // u10.16
      st.have_material = true;
      st.bank = (st.bank + 1) % st.tables.size();
    } else if (const auto* t = std::get_if<TriangleCmd>(&cmd)) {
      st.triangle = *t;
      st.have_triangle = true;
    } else if (const auto* tb = std::get_if<TableCmd>(&cmd)) {
      if (c.specular.kind == SpecularUnitKind::kLut) {
        for (size_t b = 0; b < st.tables.size(); ++b) {
          if (tb->per_material && b != st.bank) continue;
          for (size_t k = 0; k < tb->entries.size(); ++k)
            st.tables[b].at(tb->base + k) = tb->entries[k];
        }
      }
    } else if (const auto* s = std::get_if<SpanCmd>(&cmd)) {
      if (!st.have_material || !st.have_triangle) {
        throw std::invalid_argument("golden: span before any tri/material command");
      }
      const Int128 dx = s->x0 - st.triangle.xo, dy = s->y - st.triangle.yo;
      // Start values: the quadratic at the first pixel and its forward differences along x,
      // exact, each quantized once into the series format.
      std::vector<int64_t> v0(series_count), d0(series_count), d2(series_count);
      for (int i = 0; i < series_count; ++i) {
        const int64_t* t = &st.triangle.coef[static_cast<size_t>(i) * 6];
        const Int128 q0 = quadratic(t, dx, dy), q1 = quadratic(t, dx + 1, dy),
                     q2 = quadratic(t, dx + 2, dy);
        v0[i] = sc_quantize(q0, fc, c.series);
        d0[i] = sc_quantize(q1 - q0, fc, c.series);
        d2[i] = sc_quantize(q2 - 2 * q1 + q0, fc, c.series);
      }
      // Saturating builds: the per-step state of each of the K lanes (README, "Throughput: pixel
      // lanes"): lane j starts at sat(v0 + j d0 + j(j-1)/2 d2) and steps by
      // D_j = sat(K d0 + (K j + K(K-1)/2) d2), D2 = sat(K^2 d2), each addition saturating. With
      // wrap every lane's value is the closed form below, whatever K.
      const int lanes = c.lanes;
      const Int128 kl = lanes;
      std::vector<std::vector<int64_t>> lane_v(static_cast<size_t>(lanes),
                                               std::vector<int64_t>(series_count));
      std::vector<std::vector<int64_t>> lane_d = lane_v;
      std::vector<int64_t> lane_d2(series_count);
      for (int i = 0; i < series_count; ++i) {
        lane_d2[i] = sc_quantize(kl * kl * d2[i], fs, c.series);
        for (int j = 0; j < lanes; ++j) {
          const Int128 jj = j;
          lane_v[j][i] = sc_quantize(v0[i] + jj * d0[i] + jj * (jj - 1) / 2 * d2[i], fs, c.series);
          lane_d[j][i] =
              sc_quantize(kl * d0[i] + (kl * jj + kl * (kl - 1) / 2) * d2[i], fs, c.series);
        }
      }
      std::vector<int64_t> values(series_count);
      for (int k = 0; k < s->length; ++k) {
        const size_t lane = static_cast<size_t>(k % lanes);
        for (int i = 0; i < series_count; ++i) {
          if (wrap) {
            const Int128 kk = k;
            values[i] = sc_quantize(v0[i] + kk * d0[i] + kk * (kk - 1) / 2 * d2[i], fs, c.series);
          } else {
            values[i] = lane_v[lane][i];
          }
        }
        Pixel px;
        px.x = s->x0 + k;
        px.y = s->y;
        px.end_of_row = s->last_in_row && k == s->length - 1;
        const int diffuse = c.diffuse_series();
        for (int ch = 0; ch < c.channels; ++ch) {
          Int128 sum = st.ambient[ch];
          for (int l = 0; l < c.lights; ++l) {
            Int128 n_dot_l = 0;
            if (c.diffuse_multiply()) {
              // One N.L series per light, truncated to the colour's fraction bits, times kd_lc
              // into the series format; it gates too.
              n_dot_l = values[l];
              if (n_dot_l > 0) {
                const int fc = std::min(fs, c.spec_colour.frac_bits());
                const FixedFormat operand{c.series.iwl + fc, c.series.iwl, true,
                                          Quantization::kTruncate, Overflow::kWrap};
                sum += sc_quantize(Int128{sc_quantize(n_dot_l, fs, operand)} *
                                       st.diffuse_colour[l * c.channels + ch],
                                   fc + c.spec_colour.frac_bits(), c.series);
              }
            } else {
              if ((st.gate_only & (1u << l)) == 0)
                sum += std::max<int64_t>(0, values[l * c.channels + ch]);
              // The gate (model/pixel_combine.h): specular only where light l's channels'
              // diffuse values sum to more than 0.
              for (int k = 0; k < c.channels; ++k) n_dot_l += values[l * c.channels + k];
            }
            if (per_light == 0) continue;  // specular kind none: no series, no specular term
            if (n_dot_l <= 0) continue;
            const int64_t spec = specular(c, st, &values[diffuse + l * per_light]);
            sum += sc_quantize(Int128{spec} * st.spec_colour[l * c.channels + ch], product_frac,
                               c.series);
          }
          px.colour[ch] = sc_quantize(sum, fs, out);
        }
        pixels.push_back(px);
        if (!wrap) {  // the lane's v <- sat(v + D) and D <- sat(D + D2), both from the old D
          std::vector<int64_t>& v = lane_v[lane];
          std::vector<int64_t>& d = lane_d[lane];
          for (int i = 0; i < series_count; ++i) {
            const int64_t old_d = d[i];
            d[i] = sc_quantize(Int128{d[i]} + lane_d2[i], fs, c.series);
            v[i] = sc_quantize(Int128{v[i]} + old_d, fs, c.series);
          }
        }
      }
    }
  }
  return pixels;
}

}  // namespace shadesim::golden
