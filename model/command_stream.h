// The command stream: the one contract between host, bit-accurate model, cycle model and RTL.
//
// Binary form (what the RTL's cmd port carries): a sequence of 64-bit words. Each command is a
// header word followed by its payload words.
//
//   header[63:56]  opcode
//   MATERIAL  0x01 header[31:16] = gate-only light mask (bit l: light l's first diffuse series
//                  is N.L for the specular gate, not added; model/pixel_combine.h),
//                  header[15:0] = payload words. Payload: ambient[channels] (series format),
//                  spec_colour[lights*channels] (spec_colour format, light-major), with
//                  UnitConfig::diffuse_colour multiply diffuse_colour[lights*channels] (the
//                  same format and order), exponent (u10.16), then unit parameters
//                  (SpecularUnit-defined, may be empty).
//   TRIANGLE  0x02 header[47:32] = xo, header[31:16] = yo (signed 16-bit origin pixel),
//                  header[15:0] = payload words (model/coef_packing.h). Payload: for each
//                  series (diffuse l-major/c-minor, then specular per light), T0 T1 T2 T3 T4 T5,
//                  each in its term's format (UnitConfig::coef_term), packed into 64-bit words
//                  as CoefLayout describes (one per word in a 33..62-bit format, several per
//                  word when narrower; never straddling a word). The quadratic in integer pixel
//                  offsets dx = x - xo, dy = y - yo is
//                  T0 + T1*dy + T2*dx + T3*dy^2 + T4*dx*dy + T5*dx^2.
//   SPAN      0x03 header[55] = last span of its scanline in this frame, header[47:32] = y,
//                  header[31:16] = x0, header[15:0] = length (>= 1). No payload, except with
//                  host span setup (UnitConfig::span_setup kHost): then StartLayout::words
//                  payload words follow, v d d2 of every series packed densely
//                  (model/start_packing.h), and the stream has no TRIANGLE.
//   TABLE     0x04 header[55] = per-material table, header[31:16] = base address,
//                  header[15:0] = entries; payload one entry/word. A per-material table belongs
//                  to the latest MATERIAL (a per-exponent LUT's reload): with material_buffers 2
//                  each material bank has its own table and a per-material TABLE writes the
//                  bank of the latest MATERIAL only; any other TABLE writes every bank. With one
//                  buffer there is one table and the bit changes nothing.
//   END_FRAME 0x0F no payload.
//
// Command port of P = UnitConfig::port_words words (1, 2, 4 or 8) per handshake: the driver cuts
// the word sequence above into beats of P consecutive words, stream word i*P + k in bits
// [64k+63:64k] of beat i. Commands straddle beats freely (no alignment, no padding between
// commands); only the last beat is padded, with zero words (opcode 0x00, NOP). The unit takes a
// beat apart over one or more cycles, one item per cycle, and accepts it (cmd_ready) on the
// cycle it takes the beat's last word. An item is
//   - the TRIANGLE coefficient words still due, as many as the beat holds (the tail), then,
//     if the beat has a word left after the triangle's last one,
//   - at most one header: a TRIANGLE header with as many of its coefficient words as follow it
//     in the beat; a SPAN, MATERIAL, TABLE or END_FRAME header; or a NOP header with the rest
//     of the beat (padding); with a span queue (tri_queue > 1) a SPAN header comes with the
//     SPAN headers right behind it in the beat, as many as the queue has room for;
//   - or else one MATERIAL or TABLE payload word (the specular slots' configuration port is
//     one word wide).
// A header that cannot go yet stays for the next cycle (the tail still goes): a SPAN waits for
// span setup (or for room in the span queue, UnitConfig::tri_queue > 1) and, without a span
// queue, never goes with its triangle's tail (its setup reads the coefficients as it is
// taken); a TRIANGLE waits for a free coefficient bank; MATERIAL and TABLE wait for an empty
// datapath (with material_buffers 2 a MATERIAL waits only until no span of the bank it switches
// to is in flight, and a per-material TABLE until no span of the latest MATERIAL's bank is). With P
// = 1 a beat is one word and every item one word.
//
// Text form: one command per line, '#' starts a comment, a first line
// "shadesim-commands 2 <config json>" carries the unit configuration so a saved stream replays
// on its own. (Version 1 differs only in its formats: a suffix-less one saturated; it is still
// read, with that meaning.)
//   material ambient A.. spec_colour S.. [diffuse_colour D..] exponent E params P..
//     [gate_only MASK] (gate_only written when not 0; absent means 0; diffuse_colour with
//     diffuse_colour multiply only)
//   tri XO YO | T0 T1 T2 T3 T4 T5 | T0 ... (one group per series)
//   span Y X0 LEN [last] [| V D D2 | ...]   (the start values with host span setup)
//   table BASE E0 E1 ... [material]   (material: a per-material table)
//   end
#pragma once

#include <cstdint>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "model/command_word.h"
#include "model/unit_config.h"

namespace shadesim {

// The text form's version (its header line); see the text form above.
inline constexpr int kCommandStreamVersion = 2;

struct MaterialCmd {
  std::vector<int64_t> ambient;      // [channels], series format
  std::vector<int64_t> spec_colour;  // [lights * channels], spec_colour format
  // kd_c L_c [lights * channels], spec_colour format, with UnitConfig::diffuse_colour multiply;
  // empty when the colour is rolled into the series.
  std::vector<int64_t> diffuse_colour;
  int64_t exponent = 0;              // u10.16
  std::vector<int64_t> unit_params;  // specular-unit defined
  // Bit l: light l's diffuse series of channel 0 carries N.L for the specular gate only
  // (PixelCombine does not add it). Bits at and above `lights` must be 0.
  uint32_t gate_only = 0;

  size_t payload_words() const {
    return ambient.size() + spec_colour.size() + diffuse_colour.size() + 1 + unit_params.size();
  }
};

struct TriangleCmd {
  int32_t xo = 0, yo = 0;
  std::vector<int64_t> coef;  // [series_per_triangle * 6], coef format
};

struct SpanCmd {
  int32_t y = 0, x0 = 0, length = 1;
  bool last_in_row = false;
  // Host span setup (UnitConfig::span_setup kHost) only: v, d, d2 of every series at the span's
  // first pixel, series format raw, in series order (model/start_packing.h). Empty otherwise.
  std::vector<int64_t> starts;
};

struct TableCmd {
  uint32_t base = 0;
  std::vector<int64_t> entries;
  bool per_material = false;  // header[55]: the table of the latest MATERIAL (see above)
};

struct EndFrameCmd {};

using Command = std::variant<MaterialCmd, TriangleCmd, SpanCmd, TableCmd, EndFrameCmd>;

// The MATERIAL exponent word: u10.16, rounded, saturating - the one definition the encoder and
// spec-error's unit measurements both quantize with.
constexpr FixedFormat kExponentFormat{26, 10, false, Quantization::kRoundNearest,
                                      Overflow::kSaturate};
constexpr int kExponentFracBits = kExponentFormat.frac_bits();
constexpr int kTermsPerSeries = 6;

// Error in a stream: names the source (file or "<binary>"), the line or word index, and what
// was expected.
class CommandStreamError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct CommandStream {
  UnitConfig config;
  std::vector<Command> commands;

  // Checks every command's payload sizes and field ranges against `config`.
  void validate(const std::string& source) const;

  std::vector<uint64_t> encode() const;
  // encode().size(), without forming the words.
  size_t word_count() const;
  static CommandStream decode(const std::vector<uint64_t>& words, const UnitConfig& config,
                              const std::string& source);

  void write_text(std::ostream& os) const;
  static CommandStream read_text(std::istream& is, const std::string& source);

  void save(const std::string& path) const;  // text form
  static CommandStream load(const std::string& path);
};

// UnitConfig <-> JSON (one line), used by the text header and by reports.
std::string config_to_json(const UnitConfig& config);
UnitConfig config_from_json(const std::string& text, const std::string& source);

}  // namespace shadesim
