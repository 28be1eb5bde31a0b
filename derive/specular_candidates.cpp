#include "derive/specular_candidates.h"

namespace shadesim {
namespace {

SpecularConfig wpow(int m, int bits, FitObjective fit) {
  SpecularConfig s;
  s.kind = SpecularUnitKind::kWpow;
  s.wpow.max_m = m;
  s.wpow.base_bits = bits;
  s.wpow.timing = UnitTiming::kPipelined;
  s.wpow.fit = fit;
  return s;
}

SpecularConfig lut(LutAddressing addressing, int addr, int entry, int interp) {
  SpecularConfig s;
  s.kind = SpecularUnitKind::kLut;
  s.lut.addressing = addressing;
  s.lut.addr_bits = addr;
  s.lut.entry_bits = entry;
  s.lut.interp_bits = interp;
  // A shared table of exp(-k (1 - t)) needs its k fitted to each exponent to meet t^n.
  if (addressing == LutAddressing::kShared) s.lut.fit = FitObjective::kAbsolute;
  return s;
}

SpecularConfig schlick(int quotient, int operand, FitObjective fit) {
  SpecularConfig s;
  s.kind = SpecularUnitKind::kSchlick;
  s.schlick.quotient_bits = quotient;
  s.schlick.operand_bits = operand;
  s.schlick.fit = fit;
  return s;
}

constexpr auto kPerN = LutAddressing::kPerExponent;
constexpr auto kShared = LutAddressing::kShared;

}  // namespace

std::vector<SpecularConfig> named_unit_candidates(SpecularUnitKind named) {
  switch (named) {
    case SpecularUnitKind::kLut:
      // By table bits (2^A x B); at equal size the shared table first (no reload per material).
      return {lut(kPerN, 10, 8, 0),    lut(kShared, 10, 12, 4), lut(kPerN, 10, 12, 4),
              lut(kShared, 10, 16, 6), lut(kPerN, 10, 16, 6),   lut(kShared, 12, 16, 6),
              lut(kPerN, 12, 16, 6)};
    case SpecularUnitKind::kSchlick:
      // Schlick's n, then n' fitted for the absolute error, then a wider divider.
      return {schlick(16, 24, FitObjective::kNone), schlick(16, 24, FitObjective::kAbsolute),
              schlick(20, 28, FitObjective::kAbsolute)};
    case SpecularUnitKind::kWpow:
      return {wpow(16, 16, FitObjective::kNone), wpow(16, 16, FitObjective::kAbsolute),
              wpow(32, 16, FitObjective::kNone), wpow(32, 16, FitObjective::kAbsolute),
              wpow(32, 20, FitObjective::kAbsolute)};
    case SpecularUnitKind::kNone:
    case SpecularUnitKind::kIdeal:
      return {};
  }
  return {};
}

std::vector<SpecularConfig> ideal_stand_ins() {
  return {wpow(16, 16, FitObjective::kAbsolute),
          wpow(32, 16, FitObjective::kNone),
          wpow(32, 16, FitObjective::kAbsolute),
          lut(kPerN, 10, 12, 4),
          lut(kShared, 10, 12, 4),
          lut(kPerN, 10, 16, 6),
          lut(kPerN, 12, 16, 6)};
}

}  // namespace shadesim
