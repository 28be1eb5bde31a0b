#include "sim/harness/random_stream.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "model/host_setup.h"
#include "model/wpow_unit.h"

namespace shadesim {

std::vector<std::string> scenario_names() {
  return {"mixed", "long", "short", "slow", "maxbp", "switch", "tiny", "edge"};
}

Scenario scenario_by_name(const std::string& name) {
  Scenario s;
  s.name = name;
  if (name == "mixed") {
    s.stim.gap_pct = 30;
    s.stim.max_gap = 6;
    s.stim.stall_pct = 30;
  } else if (name == "long") {
    s.shape.rows = 6;
    s.shape.full_rows = true;
    s.shape.p_new_triangle = 1.0;
    s.stim.gap_pct = 10;
    s.stim.max_gap = 3;
    s.stim.stall_pct = 10;
  } else if (name == "short") {
    s.shape.rows = 200;
    s.shape.max_spans_per_row = 8;
    s.shape.min_len = 1;
    s.shape.max_len = 3;
    s.shape.p_new_triangle = 0.2;
    s.shape.p_material = 0.01;
  } else if (name == "slow") {
    s.shape.rows = 16;
    s.shape.max_len = 50;
    s.stim.gap_pct = 100;
    s.stim.max_gap = 40;
  } else if (name == "maxbp") {
    s.shape.rows = 16;
    s.shape.max_len = 100;
    s.stim.stall_pct = 90;
  } else if (name == "switch") {
    s.shape.rows = 32;
    s.shape.max_len = 30;
    s.shape.p_material = 0.5;
    s.stim.gap_pct = 20;
    s.stim.max_gap = 4;
    s.stim.stall_pct = 20;
  } else if (name == "tiny") {
    // About 10,000 small triangles: every span gets its own, 1..4 pixels long.
    s.shape.rows = 2200;
    s.shape.max_spans_per_row = 8;
    s.shape.min_len = 1;
    s.shape.max_len = 4;
    s.shape.p_new_triangle = 1.0;
    s.shape.p_material = 0.002;
    s.stim.gap_pct = 5;
    s.stim.max_gap = 3;
    s.stim.stall_pct = 10;
  } else if (name == "edge") {
    s.shape.rows = 8;
    s.shape.frames = 3;
    s.shape.edge = true;
    s.shape.max_spans_per_row = 4;
    s.shape.max_len = 64;
    s.shape.p_material = 0.15;
    s.shape.p_wild = 0.1;
    s.stim.gap_pct = 20;
    s.stim.max_gap = 4;
    s.stim.stall_pct = 30;
  } else {
    std::string all;
    for (const auto& n : scenario_names()) all += (all.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown scenario '" + name + "'; expected one of " + all);
  }
  return s;
}

CommandStream random_stream(const UnitConfig& config, const StreamShape& shape, uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto uni = [&rng](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  auto irange = [&rng](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  auto chance = [&](double p) { return uni(0.0, 1.0) < p; };
  // The MATERIAL's gate-only mask has a generator of its own, so every other field of a seed's
  // stream stays what it was before the mask existed.
  std::mt19937_64 gate_rng(seed ^ 0x9E3779B97F4A7C15u);

  CommandStream cs;
  cs.config = config;
  // Host span setup: the same frame with unit setup, then each span's start values from its
  // triangle (model/host_setup.h), so a seed's pixels do not depend on the knob.
  cs.config.span_setup = SpanSetupSite::kUnit;
  const int width = 1 << config.xy_bits;
  const int series = config.series_per_triangle();

  // Specular units: random table contents and unit parameters within the model's legal ranges,
  // and non-zero specular colours (the ideal unit is pow() in double, not hardware: the RTL slot
  // outputs 0 for it, so its streams keep spec_colour = 0). A unit with no specular term (none)
  // gets colours and gate-only masks too, which model and RTL must both ignore, and the diffuse
  // series of a unit without a specular term (none, ideal) span their whole range.
  const SpecularConfig& spec = config.specular;
  const bool spec_colours = spec.kind != SpecularUnitKind::kIdeal;
  const bool has_spec_hw = spec_colours && spec.kind != SpecularUnitKind::kNone;
  const int lut_size = 1 << spec.lut.addr_bits;
  // per_material: the table of the latest MATERIAL (with two material buffers its bank only).
  auto lut_table = [&](int base, int n, bool per_material) {
    TableCmd t;
    t.base = static_cast<uint32_t>(base);
    t.per_material = per_material;
    const uint64_t limit = uint64_t{1} << spec.lut.entry_bits;
    for (int i = 0; i < n; ++i) t.entries.push_back(static_cast<int64_t>(rng() % limit));
    cs.commands.emplace_back(t);
  };
  auto material = [&]() {
    if (chance(shape.p_table)) {
      if (spec.kind == SpecularUnitKind::kLut) {
        const int n = std::min(irange(1, 8), lut_size);
        lut_table(irange(0, lut_size - n), n, chance(0.5));
      } else {
        TableCmd t;  // ignored by units without a table
        t.base = static_cast<uint32_t>(irange(0, 1023));
        const int n = irange(1, 8);
        for (int i = 0; i < n; ++i) t.entries.push_back(static_cast<int64_t>(rng() >> 1));
        cs.commands.emplace_back(t);
      }
    }
    MaterialCmd m;
    // Edge: a negative ambient makes totals negative (the output clamps them to 0).
    for (int c = 0; c < config.channels; ++c) {
      const bool negative = shape.edge && chance(0.3);
      m.ambient.push_back(config.series.from_double(negative ? uni(-0.6, 0.0) : uni(0.0, 0.25)));
    }
    m.spec_colour.assign(static_cast<size_t>(config.lights * config.channels), 0);
    if (spec_colours) {
      for (auto& v : m.spec_colour) {
        v = config.spec_colour.from_double(shape.edge ? uni(0.2, 0.9) : uni(0.0, 0.5));
      }
    }
    // A quarter of the materials with spec hardware: a random set of gate-only lights.
    if (spec_colours && gate_rng() % 4 == 0) {
      m.gate_only = static_cast<uint32_t>(gate_rng() % (uint64_t{1} << config.lights));
    }
    // Diffuse colour multiply: every light's one series gates itself (no gate-only light), and
    // the colours it is multiplied by go up to 2 (an edge beyond kd L <= 1).
    if (config.diffuse_multiply()) {
      m.gate_only = 0;
      for (int i = 0; i < config.colours(); ++i) {
        m.diffuse_colour.push_back(
            config.spec_colour.from_double(shape.edge ? uni(0.0, 1.99) : uni(0.0, 1.0)));
      }
    }
    m.exponent = int64_t{irange(1, 200)} << kExponentFracBits;
    // Edge: fractional exponents over the whole u10.16 range, every shift the units accept.
    if (shape.edge) {
      m.exponent = static_cast<int64_t>(rng() % (int64_t{1000} << kExponentFracBits)) + 1;
    }
    const int max_shift =
        shape.edge ? config.series.frac_bits() : std::min(4, config.series.frac_bits());
    if (spec.kind == SpecularUnitKind::kLut && chance(0.5)) {
      m.unit_params = {irange(0, max_shift)};
    } else if (spec.kind == SpecularUnitKind::kWpow && chance(0.5)) {
      m.unit_params = {irange(0, shape.edge ? max_shift : std::min(3, config.series.frac_bits())),
                       irange(0, WpowUnit::stages(spec.wpow))};
    }
    cs.commands.emplace_back(m);
    // A per-material reload after the MATERIAL, as a per-exponent LUT's stream has: with two
    // material buffers it loads the new bank while the old material's pixels still read theirs.
    if (spec.kind == SpecularUnitKind::kLut && chance(shape.p_table)) {
      const int n = std::min(irange(1, 8), lut_size);
      lut_table(irange(0, lut_size - n), n, true);
    }
  };
  // Edge triangles: per series one of five kinds - ordinary (most often, so the specular term
  // still shows in most pixels); a large value (totals above 1, the output saturates); a value
  // at the top of the series range with a rising slope and curvature (the series leaves its
  // format: wraps, or saturates in :sat builds); a negative value (the diffuse clamp at 0); a
  // flat value just above 0.
  // Coefficients stay inside the coef format.
  // The lowest T0 of series s. A specular unit's diffuse series start at or above 0: the
  // specular term shows only where light l's diffuse values sum to more than 0 (the N.L gate,
  // model/pixel_combine.h), and the slopes and the edge kinds below still take them negative.
  auto diffuse_lo = [&](int s) { return has_spec_hw && s < config.diffuse_series() ? 0.0 : -0.3; };
  // Their slopes and curvatures are 1/256 of the others', so over a long span they stay in the
  // range where the specular term is neither gated off nor saturated.
  auto slope = [&](int s) { return has_spec_hw && s < config.diffuse_series() ? 1.0 / 256 : 1.0; };
  const double coef_top = std::ldexp(1.0, config.coef.iwl - 1) * 0.999;
  const double series_top = std::ldexp(1.0, config.series.iwl - 1);
  auto edge_terms = [&](TriangleCmd& t) {
    for (int s = 0; s < series; ++s) {
      const double base = has_spec_hw && s < config.diffuse_series() ? 0.5 / config.lights : 1.0;
      const double g = slope(s);
      double terms[kTermsPerSeries] = {uni(diffuse_lo(s), 1.2) * base, uni(-1, 1) / 256 * g,
                                       uni(-1, 1) / 256 * g,           uni(-1, 1) / 16384 * g,
                                       uni(-1, 1) / 16384 * g,         uni(-1, 1) / 16384 * g};
      const int kind = irange(0, 9);
      if (kind == 6) {
        // Flat, 1-7 series LSBs above 0: positive, yet 0 in a Schlick divider's narrower
        // operand, so beside a kind-9 denominator the divider's rules for num > 0, den <= 0 and
        // num_op = 0 are all in play. The LSB count comes from the slope already drawn: no
        // extra draw, so every stream keeps the spans (and the cycle counts) it had before.
        const int lsbs = 1 + static_cast<int>(std::fabs(terms[1]) * 256 / g * 7);
        terms[0] = std::ldexp(std::min(lsbs, 7), -config.series.frac_bits());
        std::fill(terms + 1, terms + kTermsPerSeries, 0.0);
      } else if (kind == 7) {
        terms[0] = uni(1.0, 3.0);
      } else if (kind == 8) {
        terms[0] = series_top * uni(0.9, 0.999);
        terms[2] = uni(0.0, 1.0) / 32;
        terms[5] = uni(0.0, 1.0) / 1024;
      } else if (kind == 9) {
        terms[0] = -uni(0.1, 2.0);
      }
      for (double& v : terms) v = std::clamp(v, -coef_top, coef_top);
      for (double v : terms) t.coef.push_back(config.coef.from_double(v));
    }
  };
  // Span setup's offsets (UnitConfig::offset_bits): an origin far off screen only where they
  // are screen-sized; otherwise within the offsets' range of the span that starts the triangle
  // (dx = x0 - xo = -offset: the offset in -hi..hi + 1; a span beyond it starts a new
  // triangle, below).
  const int ofs_hi = (1 << (config.offset_bits - 1)) - 1;
  const bool wide_offsets = config.offset_bits == UnitConfig::kMaxOffsetBits;
  int32_t origin_x = 0, origin_y = 0;
  auto triangle = [&](int x0, int y) {
    TriangleCmd t;
    const bool wild = chance(shape.p_wild);
    if (wild && wide_offsets && chance(0.5)) {
      t.xo = chance(0.5) ? -32768 : 32767;
      t.yo = chance(0.5) ? -32768 : 32767;
    } else {
      t.xo = x0 + std::clamp(irange(-40, 40), -ofs_hi, ofs_hi + 1);
      t.yo = y + std::clamp(irange(-40, 40), -ofs_hi, ofs_hi + 1);
    }
    origin_x = t.xo;
    origin_y = t.yo;
    const double k = wild ? 64.0 : 1.0;
    if (shape.edge && !wild) {
      edge_terms(t);
      cs.commands.emplace_back(t);
      return;
    }
    for (int s = 0; s < series; ++s) {
      // With a specular unit, keep most pixels below the output's saturation so the specular
      // term shows in the bits: diffuse terms scaled down by the light count.
      const double base = has_spec_hw && s < config.diffuse_series() ? 0.5 / config.lights : 1.0;
      const double g = slope(s) * k;
      const double terms[kTermsPerSeries] = {uni(diffuse_lo(s), 1.2) * base * k,
                                             uni(-1, 1) / 256 * g,
                                             uni(-1, 1) / 256 * g,
                                             uni(-1, 1) / 16384 * g,
                                             uni(-1, 1) / 16384 * g,
                                             uni(-1, 1) / 16384 * g};
      // A narrowed term (coef_term_iwl) saturates: wild values reach its limits.
      for (int k = 0; k < kTermsPerSeries; ++k)
        t.coef.push_back(config.coef_term(k).from_double(terms[k]));
    }
    cs.commands.emplace_back(t);
  };

  // The LUT's RAM has no reset: load every entry before the first pixel.
  if (spec.kind == SpecularUnitKind::kLut) lut_table(0, lut_size, false);
  material();
  bool have_triangle = false;
  for (int frame = 0; frame < shape.frames; ++frame) {
    if (frame > 0) cs.commands.emplace_back(EndFrameCmd{});
    // Edge: the frame's rows run off the bottom of the screen and wrap to the top.
    int y = shape.edge ? width - irange(1, shape.rows) : irange(0, 3);
    for (int row = 0; row < shape.rows; ++row, y = (y + 1) % width) {
      const int spans = shape.full_rows ? 1 : irange(1, shape.max_spans_per_row);
      int x = shape.full_rows ? 0 : irange(0, 16);
      // Edge rows: one span across the whole screen width, or spans at the right edge.
      const int edge_kind = shape.edge ? irange(0, 3) : -1;
      if (edge_kind == 1) x = width - irange(1, shape.max_len) * spans;
      if (edge_kind == 2) x = width - irange(1, 4);
      x = std::max(x, 0);
      for (int s = 0; s < spans && x < width; ++s) {
        SpanCmd span;
        span.y = y;
        span.x0 = x;
        if (edge_kind == 0) {
          span.x0 = 0;
          span.length = width;
        } else if (shape.full_rows) {
          span.length = std::min(width, 2048);
        } else {
          span.length = std::min(irange(shape.min_len, shape.max_len), width - x);
        }
        x = span.x0 + span.length + (edge_kind > 0 ? 0 : irange(0, 8));
        span.last_in_row = s == spans - 1 || x >= width;
        if (chance(shape.p_material)) material();
        if (!have_triangle || chance(shape.p_new_triangle) ||
            !config.offsets_fit(span.x0 - origin_x, span.y - origin_y)) {
          triangle(span.x0, span.y);
        }
        have_triangle = true;
        cs.commands.emplace_back(span);
        if (span.last_in_row) break;
      }
    }
  }
  cs.commands.emplace_back(EndFrameCmd{});
  cs.validate("random_stream");
  if (config.host_setup()) {
    CommandStream host = with_host_setup(cs);
    host.validate("random_stream");
    return host;
  }
  return cs;
}

}  // namespace shadesim
