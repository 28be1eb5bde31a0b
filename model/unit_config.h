// The configuration of one shading unit: every width and structural choice. In the model these
// are run-time values (a width sweep needs no rebuild); in the RTL they are parameters of
// shade_unit with the same names.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/fixed_point.h"
#include "model/specular_config.h"

namespace shadesim {

// Where a span's series start values (v, d, d2) are formed: in the unit's span setup from the
// triangle's coefficients (kUnit), or by the host, which sends them after each SPAN header
// (kHost; model/start_packing.h): the unit then has no coefficient bank and no span setup.
enum class SpanSetupSite : uint8_t { kUnit, kHost };

// How a material's diffuse colour kd_c L_c reaches the pixel: rolled into the series (kSeries:
// one diffuse series per light and channel, the host scales each by its colour), or multiplied
// in PixelCombine (kMultiply: one N.L series per light; the MATERIAL carries kd_c L_c per light
// and channel in the spec_colour format, and each pixel takes max(0, N.L) x kd_c L_c). With
// three channels kMultiply has a third of the diffuse series, so a third of their span setup,
// engines and start values, for a small multiply per light and channel.
enum class DiffuseColour : uint8_t { kSeries, kMultiply };

struct UnitConfig {
  // Structure: "model only what a scene needs" - a grey scene uses one channel, one light.
  int channels = 1;  // 1 (grey) or 3 (RGB)
  int lights = 1;    // directional lights, each with its own diffuse and specular series

  // Screen coordinates: unsigned, image up to 2^xy_bits pixels on a side.
  int xy_bits = 12;
  // Span setup's offsets dx = x0 - xo, dy = y - yo of a span's first pixel from its triangle's
  // origin: signed, offset_bits wide (-2^(offset_bits-1) .. 2^(offset_bits-1) - 1). They size
  // every product in span setup (its squares are 2 * offset_bits wide), so a unit sized to its
  // scene's triangles is far smaller than one sized to the screen; the encoder re-origins a
  // triangle whose spans do not fit (EncodeStats::reorigins) and CommandStream::validate rejects
  // a stream that breaks it. 17: any origin in the image, any span start (2^15 + 2^15 - 1).
  int offset_bits = 17;
  static constexpr int kMaxOffsetBits = 17;

  // Per-triangle Taylor coefficients T0..T5 as loaded from the command stream. Wrapping is
  // exact here: span setup multiplies them only by integers, so every sum is right modulo
  // 2^iwl, and a pixel value that lies in range comes out right even when a coefficient of a
  // sliver triangle (huge gradient, origin outside it) does not fit.
  FixedFormat coef{36, 4, true, Quantization::kRoundNearest, Overflow::kWrap};
  // Coefficient packing: the integer bits of each term T0..T5 (empty: every term in `coef`).
  // A term keeps coef's fraction bits and needs only the integer bits its values reach - a
  // second-order term of a small triangle far fewer than T0 - so it takes fewer bits of the
  // command stream (model/coef_packing.h) and the triangle fewer words. A term narrower than
  // coef saturates (its products are not exact modulo 2^iwl); the unit sign-extends it.
  std::vector<int> coef_term_iwl;
  // Forward-difference accumulators v, d, d2. Span setup rounds its exact start values into
  // this format with its quantization rule; the per-pixel additions follow its overflow rule.
  FixedFormat series{32, 4, true, Quantization::kTruncate, Overflow::kWrap};
  // Specular colour (ks * light colour) per light and channel, multiplied by the unit's output.
  FixedFormat spec_colour{13, 1, false, Quantization::kRoundNearest, Overflow::kSaturate};
  // Output code width per channel; a code c stands for c / 2^out_bits (saturating at the top).
  int out_bits = 8;

  SpecularConfig specular;

  // Throughput structure (the RTL's timing, not its numbers: pixels do not depend on these).
  // Command port width: 64-bit words per handshake (a beat), 1, 2, 4 or 8. How the stream's words
  // fill beats and how many the decoder takes per cycle: model/command_stream.h.
  int port_words = 1;
  // Triangle queue: coefficient banks (1..8). With more than one, SPAN headers wait in a span
  // queue of 4 per bank, so the port loads the next triangles while earlier spans still run.
  int tri_queue = 1;
  // Pixel lanes: pixels of one span leaving per clock, 1, 2 or 4 (model/lane_fanout.h). Lane j of
  // a beat is pixel x + j; each lane steps its own engines by `lanes` pixels. With a wrapping
  // series the pixels equal the one-lane unit's bit for bit; saturating, see LaneFanout.
  int lanes = 1;
  // Material buffers, 1 or 2. With 1 a MATERIAL or TABLE header waits until the datapath is
  // empty. With 2 the per-material registers (ambient, spec_colour, the specular unit's
  // parameters) have two banks and every span carries the bank of the latest MATERIAL: a
  // MATERIAL switches to the other bank and waits only while an in-flight span still reads that
  // one. The LUT's table has a bank per buffer too: a per-material TABLE (header bit 55, a
  // per-exponent reload) writes the latest MATERIAL's bank and waits only for that bank's spans;
  // any other TABLE writes both and waits for the empty datapath (model/command_stream.h).
  // Each MATERIAL defines every other banked field, so the encoder's pixels do not depend on
  // this either.
  int material_buffers = 1;
  // Span setup in the unit (default) or on the host. With kHost the stream has no TRIANGLE
  // command; every SPAN carries its start values (3 x series_per_triangle in the series format),
  // which the host computes with the model's own SpanSetup, so pixels are those of kUnit for the
  // same widths. The unit trades its span setup and coefficient banks for a start-value register
  // set and more command words per span (cycles per pixel: the cycle model counts them).
  // offset_bits keeps its meaning for the encoder's origins (so pixels do not change with the
  // knob) but sizes no hardware; tri_queue must be 1 (there are no coefficient banks).
  SpanSetupSite span_setup = SpanSetupSite::kUnit;
  bool host_setup() const { return span_setup == SpanSetupSite::kHost; }
  // Host span setup only (a unit-setup unit has no start bank and ignores it, so the host and
  // unit sites of one config differ in span_setup alone): the start bank's entries (RTL
  // START_DEPTH, 1 or 2). With two the next span's words stream in while one span waits and one
  // runs; one entry halves the bank's registers and costs cycles. `shadesim cycles SCENE
  // --config OWN.json` on the shipped scenes' own units (`shadesim config SCENE --json OWN.json`)
  // gives 1.001 cycles/px for specular and torus and 1.044 for suzanne at two, 1.233, 1.133 and
  // 1.220 at one (docs/history/area.md).
  int start_depth = kStartDepth;
  static constexpr int kStartDepth = 2;
  DiffuseColour diffuse_colour = DiffuseColour::kSeries;
  bool diffuse_multiply() const { return diffuse_colour == DiffuseColour::kMultiply; }
  // Pipelining (the RTL's clock, not its numbers: pixels do not depend on it). combine_stages:
  // register stages in pixel_combine, 0, 1 or 2 (shade_unit COMBINE_STAGES). 1 registers each
  // light's terms (the diffuse and specular products, gated) before their sum with its rounding;
  // 2 also registers the raw products before their rounding and gate, and sums each light's two
  // terms before the second register. Each adds one cycle of latency from the slot to the pix
  // register and shortens the path that ends there (docs/area.md: the critical path `shadesim
  // area` prints).
  int combine_stages = 0;

  // Term t's format (0..5): coef's, or coef narrowed to coef_term_iwl[t] integer bits.
  FixedFormat coef_term(int t) const;
  int coef_term_bits(int t) const { return coef_term(t).wl; }
  // Whether span setup can take the offsets (dx, dy): each fits offset_bits signed.
  bool offsets_fit(int64_t dx, int64_t dy) const {
    const int64_t lo = -(int64_t{1} << (offset_bits - 1)), hi = -lo - 1;
    return dx >= lo && dx <= hi && dy >= lo && dy <= hi;
  }

  int diffuse_series() const { return diffuse_multiply() ? lights : lights * channels; }
  // Colour words per light and channel (spec_colour; with kMultiply the diffuse ones too).
  int colours() const { return lights * channels; }
  int specular_series() const { return lights * specular.series_per_light(); }
  int series_per_triangle() const { return diffuse_series() + specular_series(); }

  // Throws std::invalid_argument naming the offending field.
  void validate() const;

  // One line, e.g. "rgb/1L coef=s4.32:rnd series=s4.28:wrap out=8 spec=ideal".
  std::string to_string() const;
};

std::string to_string(SpanSetupSite s);  // "unit" or "host"
// Throws std::invalid_argument naming `what` for anything but "unit" and "host".
SpanSetupSite parse_span_setup(const std::string& text, const std::string& what);
std::string to_string(DiffuseColour d);  // "series" or "multiply"
// Throws std::invalid_argument naming `what` for anything but "series" and "multiply".
DiffuseColour parse_diffuse_colour(const std::string& text, const std::string& what);

}  // namespace shadesim
