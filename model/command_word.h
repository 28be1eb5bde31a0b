// One 64-bit word of the command stream: the one C++ definition of the header layout
// (model/command_stream.h documents the commands; rtl/shade_pkg.sv is the RTL's twin). The
// encoder, the decoder, the cycle model and the co-simulation driver all read and write header
// fields through CommandWord, and nowhere else.
#pragma once

#include <cstdint>

namespace shadesim {

enum class Opcode : uint8_t {
  kNop = 0x00,  // beat padding only (never in a stream): it and the rest of its beat are skipped
  kMaterial = 0x01,
  kTriangle = 0x02,
  kSpan = 0x03,
  kTable = 0x04,
  kEndFrame = 0x0F,
};

struct CommandWord {
  static constexpr int kOpcodeLsb = 56;            // [63:56]
  static constexpr int kFieldBits = 16;            // every field below is 16 bits wide
  static constexpr int kCountLsb = 0;              // [15:0]  payload words; SPAN: length
  static constexpr int kMidLsb = 16;               // [31:16] TRIANGLE yo, SPAN x0, TABLE base,
                                                   //         MATERIAL gate-only light mask
  static constexpr int kHighLsb = 32;              // [47:32] TRIANGLE xo, SPAN y
  static constexpr int kSpanLastBit = 55;          // SPAN: last span of its scanline
  static constexpr int kTablePerMaterialBit = 55;  // TABLE: the table of the latest MATERIAL
  static constexpr uint64_t kFieldMask = 0xFFFF;

  uint64_t bits = 0;

  constexpr unsigned opcode() const { return static_cast<unsigned>(bits >> kOpcodeLsb) & 0xFF; }
  constexpr bool is(Opcode op) const { return opcode() == static_cast<unsigned>(op); }
  constexpr unsigned count() const { return field(kCountLsb); }
  // TRIANGLE: the origin pixel, signed.
  constexpr int32_t tri_xo() const { return static_cast<int16_t>(field(kHighLsb)); }
  constexpr int32_t tri_yo() const { return static_cast<int16_t>(field(kMidLsb)); }
  // SPAN
  constexpr int32_t span_y() const { return static_cast<int32_t>(field(kHighLsb)); }
  constexpr int32_t span_x0() const { return static_cast<int32_t>(field(kMidLsb)); }
  constexpr int32_t span_length() const { return static_cast<int32_t>(count()); }
  constexpr bool span_last() const { return ((bits >> kSpanLastBit) & 1) != 0; }
  // TABLE
  constexpr uint32_t table_base() const { return field(kMidLsb); }
  constexpr bool table_per_material() const { return ((bits >> kTablePerMaterialBit) & 1) != 0; }
  // MATERIAL: bit l set = light l's first diffuse series carries N.L for the specular gate only
  // (the material has no diffuse colour for that light; model/pixel_combine.h has the rule).
  constexpr uint32_t material_gate_only() const { return field(kMidLsb); }

  // Header words. Fields are masked to 16 bits; range checks are the stream validator's job.
  static constexpr CommandWord header(Opcode op, uint64_t count, uint64_t mid = 0,
                                      uint64_t high = 0) {
    return {static_cast<uint64_t>(op) << kOpcodeLsb | (high & kFieldMask) << kHighLsb |
            (mid & kFieldMask) << kMidLsb | (count & kFieldMask) << kCountLsb};
  }
  static constexpr CommandWord material(uint64_t count, uint64_t gate_only = 0) {
    return header(Opcode::kMaterial, count, gate_only);
  }
  static constexpr CommandWord triangle(int32_t xo, int32_t yo, uint64_t count) {
    return header(Opcode::kTriangle, count, static_cast<uint64_t>(yo), static_cast<uint64_t>(xo));
  }
  static constexpr CommandWord span(int32_t y, int32_t x0, int32_t length, bool last) {
    CommandWord w = header(Opcode::kSpan, static_cast<uint64_t>(length), static_cast<uint64_t>(x0),
                           static_cast<uint64_t>(y));
    if (last) w.bits |= uint64_t{1} << kSpanLastBit;
    return w;
  }
  static constexpr CommandWord table(uint32_t base, uint64_t count, bool per_material = false) {
    CommandWord w = header(Opcode::kTable, count, base);
    if (per_material) w.bits |= uint64_t{1} << kTablePerMaterialBit;
    return w;
  }
  static constexpr CommandWord end_frame() { return header(Opcode::kEndFrame, 0); }

 private:
  constexpr unsigned field(int lsb) const {
    return static_cast<unsigned>((bits >> lsb) & kFieldMask);
  }
};

}  // namespace shadesim
