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

namespace {

// One random stream, command by command. The seed's stream is the sequence of draws in the order
// they are made: every function below keeps its draws in the order they have always had, so a
// seed gives the stream (and the pixels and cycles) it always gave.
class RandomStreamBuilder {
 public:
  RandomStreamBuilder(const UnitConfig& config, const StreamShape& shape, uint64_t seed);
  CommandStream build();

 private:
  double uni(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  int irange(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  bool chance(double p) { return uni(0.0, 1.0) < p; }

  void frame(int index);
  void row(int y);
  int span_length(int x, int edge_kind);
  void add_span(const SpanCmd& span);
  void lut_table(int base, int n, bool per_material);
  void material();
  void table_before_material();
  MaterialCmd random_material();
  void draw_unit_params(MaterialCmd& m);
  void triangle(int x0, int y);
  void place_origin(TriangleCmd& t, int x0, int y, bool wild);
  void ordinary_terms(TriangleCmd& t, double k);
  void edge_terms(TriangleCmd& t);
  void apply_edge_kind(double* terms, double g);
  void exact_ratio(double* terms, int s);
  void short_table();
  // A diffuse series of a unit with a specular term (its N.L gate reads them).
  bool gating_diffuse(int s) const { return has_spec_hw_ && s < config_.diffuse_series(); }
  // The lowest T0 of series s. A specular unit's diffuse series start at or above 0: the
  // specular term shows only where light l's diffuse values sum to more than 0 (the N.L gate,
  // model/pixel_combine.h), and the slopes and the edge kinds below still take them negative.
  double diffuse_lo(int s) const { return gating_diffuse(s) ? 0.0 : -0.3; }
  // Their slopes and curvatures are 1/256 of the others', so over a long span they stay in the
  // range where the specular term is neither gated off nor saturated.
  double slope(int s) const { return gating_diffuse(s) ? 1.0 / 256 : 1.0; }
  // With a specular unit, keep most pixels below the output's saturation so the specular term
  // shows in the bits: diffuse terms scaled down by the light count.
  double diffuse_scale(int s) const { return gating_diffuse(s) ? 0.5 / config_.lights : 1.0; }

  const UnitConfig& config_;
  const StreamShape& shape_;
  std::mt19937_64 rng_;
  // The MATERIAL's gate-only mask has a generator of its own, so every other field of a seed's
  // stream is the same with or without it (saved seeds keep their streams).
  std::mt19937_64 gate_rng_;
  // So have the edge scenario's corners drawn apart from its other draws (exact_ratio,
  // short_table), for the same reason.
  std::mt19937_64 corner_rng_;
  double ratio_den_ = 0.0;  // the pair's denominator, drawn with its numerator
  CommandStream cs_;
  const int width_;
  const int series_;
  // Specular units: random table contents and unit parameters within the model's legal ranges,
  // and non-zero specular colours (the ideal unit is pow() in double, not hardware: the RTL slot
  // outputs 0 for it, so its streams keep spec_colour = 0). A unit with no specular term (none)
  // gets colours and gate-only masks too, which model and RTL must both ignore, and the diffuse
  // series of a unit without a specular term (none, ideal) span their whole range.
  const SpecularConfig& spec_;
  const bool spec_colours_;
  const bool has_spec_hw_;
  const int lut_size_;
  // Coefficients stay inside the coef format.
  const double coef_top_;
  const double series_top_;
  // Span setup's offsets (UnitConfig::offset_bits): an origin far off screen only where they
  // are screen-sized; otherwise within the offsets' range of the span that starts the triangle
  // (dx = x0 - xo = -offset: the offset in -hi..hi + 1; a span beyond it starts a new
  // triangle, add_span).
  const int ofs_hi_;
  const bool wide_offsets_;
  int32_t origin_x_ = 0, origin_y_ = 0;
  bool have_triangle_ = false;
};

RandomStreamBuilder::RandomStreamBuilder(const UnitConfig& config, const StreamShape& shape,
                                         uint64_t seed)
    : config_(config),
      shape_(shape),
      rng_(seed),
      gate_rng_(seed ^ 0x9E3779B97F4A7C15u),
      corner_rng_(seed ^ 0xC2B2AE3D27D4EB4Fu),
      width_(1 << config.xy_bits),
      series_(config.series_per_triangle()),
      spec_(config.specular),
      spec_colours_(spec_.kind != SpecularUnitKind::kIdeal),
      has_spec_hw_(spec_colours_ && spec_.kind != SpecularUnitKind::kNone),
      lut_size_(1 << spec_.lut.addr_bits),
      coef_top_(std::ldexp(1.0, config.coef.iwl - 1) * 0.999),
      series_top_(std::ldexp(1.0, config.series.iwl - 1)),
      ofs_hi_((1 << (config.offset_bits - 1)) - 1),
      wide_offsets_(config.offset_bits == UnitConfig::kMaxOffsetBits) {
  cs_.config = config;
  // Host span setup: the same frame with unit setup, then each span's start values from its
  // triangle (model/host_setup.h), so a seed's pixels do not depend on the knob.
  cs_.config.span_setup = SpanSetupSite::kUnit;
}

CommandStream RandomStreamBuilder::build() {
  // The LUT's RAM has no reset: load every entry before the first pixel.
  if (spec_.kind == SpecularUnitKind::kLut) lut_table(0, lut_size_, false);
  material();
  for (int f = 0; f < shape_.frames; ++f) frame(f);
  cs_.commands.emplace_back(EndFrameCmd{});
  cs_.validate("random_stream");
  if (config_.host_setup()) {
    CommandStream host = with_host_setup(cs_);
    host.validate("random_stream");
    return host;
  }
  return cs_;
}

void RandomStreamBuilder::frame(int index) {
  if (index > 0) cs_.commands.emplace_back(EndFrameCmd{});
  // Edge: the frame's rows run off the bottom of the screen and wrap to the top.
  int y = shape_.edge ? width_ - irange(1, shape_.rows) : irange(0, 3);
  for (int r = 0; r < shape_.rows; ++r, y = (y + 1) % width_) row(y);
}

void RandomStreamBuilder::row(int y) {
  const int spans = shape_.full_rows ? 1 : irange(1, shape_.max_spans_per_row);
  int x = shape_.full_rows ? 0 : irange(0, 16);
  // Edge rows: one span across the whole screen width, or spans at the right edge.
  const int edge_kind = shape_.edge ? irange(0, 3) : -1;
  if (edge_kind == 1) x = width_ - irange(1, shape_.max_len) * spans;
  if (edge_kind == 2) x = width_ - irange(1, 4);
  x = std::max(x, 0);
  for (int s = 0; s < spans && x < width_; ++s) {
    SpanCmd span;
    span.y = y;
    span.x0 = edge_kind == 0 ? 0 : x;
    span.length = span_length(x, edge_kind);
    x = span.x0 + span.length + (edge_kind > 0 ? 0 : irange(0, 8));
    span.last_in_row = s == spans - 1 || x >= width_;
    add_span(span);
    if (span.last_in_row) break;
  }
}

int RandomStreamBuilder::span_length(int x, int edge_kind) {
  if (edge_kind == 0) return width_;
  if (shape_.full_rows) return std::min(width_, 2048);
  return std::min(irange(shape_.min_len, shape_.max_len), width_ - x);
}

void RandomStreamBuilder::add_span(const SpanCmd& span) {
  if (chance(shape_.p_material)) material();
  if (!have_triangle_ || chance(shape_.p_new_triangle) ||
      !config_.offsets_fit(span.x0 - origin_x_, span.y - origin_y_)) {
    triangle(span.x0, span.y);
  }
  have_triangle_ = true;
  cs_.commands.emplace_back(span);
}

// per_material: the table of the latest MATERIAL (with two material buffers its bank only).
void RandomStreamBuilder::lut_table(int base, int n, bool per_material) {
  TableCmd t;
  t.base = static_cast<uint32_t>(base);
  t.per_material = per_material;
  const uint64_t limit = uint64_t{1} << spec_.lut.entry_bits;
  for (int i = 0; i < n; ++i) t.entries.push_back(static_cast<int64_t>(rng_() % limit));
  cs_.commands.emplace_back(t);
}

void RandomStreamBuilder::material() {
  if (chance(shape_.p_table)) table_before_material();
  if (shape_.edge && corner_rng_() % 3 == 0) short_table();
  cs_.commands.emplace_back(random_material());
  // A per-material reload after the MATERIAL, as a per-exponent LUT's stream has: with two
  // material buffers it loads the new bank while the old material's pixels still read theirs.
  if (spec_.kind == SpecularUnitKind::kLut && chance(shape_.p_table)) {
    const int n = std::min(irange(1, 8), lut_size_);
    lut_table(irange(0, lut_size_ - n), n, true);
  }
}

void RandomStreamBuilder::table_before_material() {
  if (spec_.kind == SpecularUnitKind::kLut) {
    const int n = std::min(irange(1, 8), lut_size_);
    lut_table(irange(0, lut_size_ - n), n, chance(0.5));
    return;
  }
  TableCmd t;  // ignored by units without a table
  t.base = static_cast<uint32_t>(irange(0, 1023));
  const int n = irange(1, 8);
  for (int i = 0; i < n; ++i) t.entries.push_back(static_cast<int64_t>(rng_() >> 1));
  cs_.commands.emplace_back(t);
}

// Edge: a TABLE of 0 or 1 entries (the payload FSM's shortest: no word at all, or its first word
// its last), per-material or shared. A LUT's entry is a legal one at a legal address.
void RandomStreamBuilder::short_table() {
  TableCmd t;
  t.per_material = corner_rng_() % 2 == 0;
  const bool one = corner_rng_() % 2 == 0;
  const uint64_t size = spec_.kind == SpecularUnitKind::kLut ? lut_size_ : 1024;
  t.base = static_cast<uint32_t>(corner_rng_() % size);
  if (one) {
    const int bits = spec_.kind == SpecularUnitKind::kLut ? spec_.lut.entry_bits : 31;
    t.entries.push_back(static_cast<int64_t>(corner_rng_() % (uint64_t{1} << bits)));
  }
  cs_.commands.emplace_back(t);
}

MaterialCmd RandomStreamBuilder::random_material() {
  MaterialCmd m;
  // Edge: a negative ambient makes totals negative (the output clamps them to 0).
  for (int c = 0; c < config_.channels; ++c) {
    const bool negative = shape_.edge && chance(0.3);
    m.ambient.push_back(config_.series.from_double(negative ? uni(-0.6, 0.0) : uni(0.0, 0.25)));
  }
  m.spec_colour.assign(static_cast<size_t>(config_.lights) * config_.channels, 0);
  if (spec_colours_) {
    for (auto& v : m.spec_colour) {
      v = config_.spec_colour.from_double(shape_.edge ? uni(0.2, 0.9) : uni(0.0, 0.5));
    }
  }
  // A quarter of the materials with spec hardware: a random set of gate-only lights.
  if (spec_colours_ && gate_rng_() % 4 == 0) {
    m.gate_only = static_cast<uint32_t>(gate_rng_() % (uint64_t{1} << config_.lights));
  }
  // Diffuse colour multiply: every light's one series gates itself (no gate-only light), and
  // the colours it is multiplied by go up to 2 (an edge beyond kd L <= 1).
  if (config_.diffuse_multiply()) {
    m.gate_only = 0;
    for (int i = 0; i < config_.colours(); ++i) {
      m.diffuse_colour.push_back(
          config_.spec_colour.from_double(shape_.edge ? uni(0.0, 1.99) : uni(0.0, 1.0)));
    }
  }
  m.exponent = int64_t{irange(1, 200)} << kExponentFracBits;
  // Edge: fractional exponents over the whole u10.16 range, every shift the units accept.
  if (shape_.edge) {
    m.exponent = static_cast<int64_t>(rng_() % (int64_t{1000} << kExponentFracBits)) + 1;
  }
  draw_unit_params(m);
  return m;
}

void RandomStreamBuilder::draw_unit_params(MaterialCmd& m) {
  const int max_shift =
      shape_.edge ? config_.series.frac_bits() : std::min(4, config_.series.frac_bits());
  if (spec_.kind == SpecularUnitKind::kLut && chance(0.5)) {
    m.unit_params = {irange(0, max_shift)};
  } else if (spec_.kind == SpecularUnitKind::kWpow && chance(0.5)) {
    m.unit_params = {irange(0, shape_.edge ? max_shift : std::min(3, config_.series.frac_bits())),
                     irange(0, WpowUnit::stages(spec_.wpow))};
  }
}

void RandomStreamBuilder::triangle(int x0, int y) {
  TriangleCmd t;
  const bool wild = chance(shape_.p_wild);
  place_origin(t, x0, y, wild);
  if (shape_.edge && !wild)
    edge_terms(t);
  else
    ordinary_terms(t, wild ? 64.0 : 1.0);
  cs_.commands.emplace_back(t);
}

void RandomStreamBuilder::place_origin(TriangleCmd& t, int x0, int y, bool wild) {
  if (wild && wide_offsets_ && chance(0.5)) {
    t.xo = chance(0.5) ? -32768 : 32767;
    t.yo = chance(0.5) ? -32768 : 32767;
  } else {
    t.xo = x0 + std::clamp(irange(-40, 40), -ofs_hi_, ofs_hi_ + 1);
    t.yo = y + std::clamp(irange(-40, 40), -ofs_hi_, ofs_hi_ + 1);
  }
  origin_x_ = t.xo;
  origin_y_ = t.yo;
}

// k: 64 for a wild triangle, whose values overflow the series.
void RandomStreamBuilder::ordinary_terms(TriangleCmd& t, double k) {
  for (int s = 0; s < series_; ++s) {
    const double g = slope(s) * k;
    const double terms[kTermsPerSeries] = {uni(diffuse_lo(s), 1.2) * diffuse_scale(s) * k,
                                           uni(-1, 1) / 256 * g,
                                           uni(-1, 1) / 256 * g,
                                           uni(-1, 1) / 16384 * g,
                                           uni(-1, 1) / 16384 * g,
                                           uni(-1, 1) / 16384 * g};
    // A narrowed term (coef_term_iwl) saturates: wild values reach its limits.
    for (int i = 0; i < kTermsPerSeries; ++i)
      t.coef.push_back(config_.coef_term(i).from_double(terms[i]));
  }
}

// Edge triangles: per series one of five kinds - ordinary (most often, so the specular term
// still shows in most pixels); a large value (totals above 1, the output saturates); a value at
// the top of the series range with a rising slope and curvature (the series leaves its format:
// wraps, or saturates in :sat builds); a negative value (the diffuse clamp at 0); a flat value
// just above 0.
void RandomStreamBuilder::edge_terms(TriangleCmd& t) {
  for (int s = 0; s < series_; ++s) {
    const double g = slope(s);
    double terms[kTermsPerSeries] = {uni(diffuse_lo(s), 1.2) * diffuse_scale(s),
                                     uni(-1, 1) / 256 * g,
                                     uni(-1, 1) / 256 * g,
                                     uni(-1, 1) / 16384 * g,
                                     uni(-1, 1) / 16384 * g,
                                     uni(-1, 1) / 16384 * g};
    apply_edge_kind(terms, g);
    if (spec_.kind == SpecularUnitKind::kSchlick) exact_ratio(terms, s);
    for (double& v : terms) v = std::clamp(v, -coef_top_, coef_top_);
    for (double v : terms) t.coef.push_back(config_.coef.from_double(v));
  }
}

void RandomStreamBuilder::apply_edge_kind(double* terms, double g) {
  const int kind = irange(0, 9);
  if (kind == 6) {
    // Flat, 1-7 series LSBs above 0: positive, yet 0 in a Schlick divider's narrower operand, so
    // beside a kind-9 denominator the divider's rules for num > 0, den <= 0 and num_op = 0 are
    // all in play. The LSB count comes from the slope already drawn: no extra draw, so every
    // stream keeps the spans (and the cycle counts) it had before.
    const int lsbs = 1 + static_cast<int>(std::fabs(terms[1]) * 256 / g * 7);
    terms[0] = std::ldexp(std::min(lsbs, 7), -config_.series.frac_bits());
    std::fill(terms + 1, terms + kTermsPerSeries, 0.0);
  } else if (kind == 7) {
    terms[0] = uni(1.0, 3.0);
  } else if (kind == 8) {
    terms[0] = series_top_ * uni(0.9, 0.999);
    terms[2] = uni(0.0, 1.0) / 32;
    terms[5] = uni(0.0, 1.0) / 1024;
  } else if (kind == 9) {
    terms[0] = -uni(0.1, 2.0);
  }
}

// Schlick: a quarter of light l's pairs flat at num / den = k / 2^v (k odd, v 1..4), den = 2^-u
// (u 1..3), every value exact in the series and the divider's operands. The restoring divider's
// partial remainder then meets the shifted denominator exactly at step v (r2 == den: the bit is
// 1 and the remainder 0), a case random operands almost never give.
void RandomStreamBuilder::exact_ratio(double* terms, int s) {
  const int at = s - config_.diffuse_series();
  if (at < 0) return;
  const bool numerator = at % 2 == 0;
  if (numerator) {
    ratio_den_ = 0.0;
    if (corner_rng_() % 4 != 0) return;
    const int u = 1 + static_cast<int>(corner_rng_() % 3);
    const int v = 1 + static_cast<int>(corner_rng_() % 4);
    const auto k = static_cast<int>(corner_rng_() % (uint64_t{1} << (v - 1))) * 2 + 1;
    ratio_den_ = std::ldexp(1.0, -u);
    terms[0] = std::ldexp(ratio_den_ * k, -v);
  } else if (ratio_den_ > 0.0) {
    terms[0] = ratio_den_;
  } else {
    return;
  }
  std::fill(terms + 1, terms + kTermsPerSeries, 0.0);
}

}  // namespace

CommandStream random_stream(const UnitConfig& config, const StreamShape& shape, uint64_t seed) {
  return RandomStreamBuilder(config, shape, seed).build();
}

}  // namespace shadesim
