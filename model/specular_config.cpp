#include "model/specular_config.h"

#include <sstream>
#include <stdexcept>

namespace shadesim {

std::string to_string(SpecularUnitKind kind) {
  switch (kind) {
    case SpecularUnitKind::kIdeal: return "ideal";
    case SpecularUnitKind::kLut: return "lut";
    case SpecularUnitKind::kSchlick: return "schlick";
    case SpecularUnitKind::kWpow: return "wpow";
  }
  return "?";
}

SpecularUnitKind parse_specular_unit(const std::string& name, const std::string& what) {
  for (auto k : {SpecularUnitKind::kIdeal, SpecularUnitKind::kLut, SpecularUnitKind::kSchlick,
                 SpecularUnitKind::kWpow}) {
    if (name == to_string(k)) return k;
  }
  throw std::invalid_argument(what + ": unknown specular unit '" + name +
                              "'; expected one of ideal, lut, schlick, wpow");
}

std::string to_string(LutIndex v) { return v == LutIndex::kTruncate ? "truncate" : "nearest"; }
std::string to_string(LutAddressing v) {
  return v == LutAddressing::kPerExponent ? "per-exponent" : "shared";
}
std::string to_string(FitObjective v) {
  switch (v) {
    case FitObjective::kNone: return "none";
    case FitObjective::kEpicentre: return "epicentre";
    case FitObjective::kAbsolute: return "absolute";
  }
  return "?";
}
std::string to_string(UnitTiming v) { return v == UnitTiming::kPipelined ? "pipelined" : "iterative"; }

namespace {
template <typename E, size_t N>
E parse_enum(const std::string& s, const std::string& what, const E (&values)[N]) {
  std::string names;
  for (E v : values) {
    if (s == to_string(v)) return v;
    names += (names.empty() ? "" : ", ") + to_string(v);
  }
  throw std::invalid_argument(what + ": unknown value '" + s + "'; expected one of " + names);
}
}  // namespace

LutIndex parse_lut_index(const std::string& s, const std::string& what) {
  const LutIndex v[] = {LutIndex::kTruncate, LutIndex::kNearest};
  return parse_enum(s, what, v);
}
LutAddressing parse_lut_addressing(const std::string& s, const std::string& what) {
  const LutAddressing v[] = {LutAddressing::kPerExponent, LutAddressing::kShared};
  return parse_enum(s, what, v);
}
FitObjective parse_fit_objective(const std::string& s, const std::string& what) {
  const FitObjective v[] = {FitObjective::kNone, FitObjective::kEpicentre, FitObjective::kAbsolute};
  return parse_enum(s, what, v);
}
UnitTiming parse_unit_timing(const std::string& s, const std::string& what) {
  const UnitTiming v[] = {UnitTiming::kPipelined, UnitTiming::kIterative};
  return parse_enum(s, what, v);
}

void SpecularConfig::validate() const {
  auto fail = [](const std::string& field, const std::string& msg) {
    throw std::invalid_argument("specular config: " + field + " " + msg);
  };
  out.validate("specular config: out");
  if (out.is_signed || out.iwl < 1) fail("out", "must be unsigned with an integer bit (holds 1.0)");
  switch (kind) {
    case SpecularUnitKind::kLut:
      if (lut.addr_bits < 1 || lut.addr_bits > 20)
        fail("lut.addr_bits", "must be 1..20, got " + std::to_string(lut.addr_bits));
      if (lut.entry_bits < 1 || lut.entry_bits > 32)
        fail("lut.entry_bits", "must be 1..32, got " + std::to_string(lut.entry_bits));
      if (lut.interp_bits < 0 || lut.interp_bits > 16)
        fail("lut.interp_bits", "must be 0..16, got " + std::to_string(lut.interp_bits));
      if (lut.interp_bits > 0 && lut.addr_bits < 2)
        fail("lut.addr_bits", "must be >= 2 with interpolation (two entries per interval)");
      if (lut.shared_range_log2 < 0 || lut.shared_range_log2 > 6)
        fail("lut.shared_range_log2", "must be 0..6, got " + std::to_string(lut.shared_range_log2));
      break;
    case SpecularUnitKind::kSchlick:
      if (schlick.quotient_bits < 1 || schlick.quotient_bits > 32)
        fail("schlick.quotient_bits", "must be 1..32, got " + std::to_string(schlick.quotient_bits));
      if (schlick.operand_bits < 2 || schlick.operand_bits > 48)
        fail("schlick.operand_bits", "must be 2..48, got " + std::to_string(schlick.operand_bits));
      break;
    case SpecularUnitKind::kWpow:
      if (wpow.max_m != 1 && wpow.max_m != 2 && wpow.max_m != 4 && wpow.max_m != 8 &&
          wpow.max_m != 16 && wpow.max_m != 32)
        fail("wpow.max_m", "must be a power of two 1..32 (4, 8 or 16 usual), got " +
                               std::to_string(wpow.max_m));
      if (wpow.base_bits < 2 || wpow.base_bits > 30)
        fail("wpow.base_bits", "must be 2..30, got " + std::to_string(wpow.base_bits));
      break;
    case SpecularUnitKind::kIdeal:
      break;
  }
}

std::string SpecularConfig::describe() const {
  std::ostringstream os;
  os << to_string(kind);
  switch (kind) {
    case SpecularUnitKind::kLut:
      os << (lut.addressing == LutAddressing::kShared ? " shared" : " per-n") << " A=" << lut.addr_bits
         << " B=" << lut.entry_bits << (lut.index == LutIndex::kTruncate ? " trn" : " near");
      if (lut.interp_bits > 0) os << " F=" << lut.interp_bits;
      if (lut.addressing == LutAddressing::kShared) {
        os << " U=2^" << lut.shared_range_log2;
        if (lut.fit != FitObjective::kNone) os << " fit=" << to_string(lut.fit);
      }
      break;
    case SpecularUnitKind::kSchlick:
      os << " Q=" << schlick.quotient_bits << " D=" << schlick.operand_bits
         << (schlick.timing == UnitTiming::kIterative ? " iter" : " pipe");
      if (schlick.fit != FitObjective::kNone) os << " fit=" << to_string(schlick.fit);
      break;
    case SpecularUnitKind::kWpow:
      os << " m=" << wpow.max_m << " B=" << wpow.base_bits
         << (wpow.timing == UnitTiming::kIterative ? " iter" : " pipe");
      if (wpow.fit != FitObjective::kNone) os << " fit=" << to_string(wpow.fit);
      break;
    case SpecularUnitKind::kIdeal:
      break;
  }
  return os.str();
}

}  // namespace shadesim
