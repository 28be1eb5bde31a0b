#include "model/specular_config.h"

#include <stdexcept>

#include "model/specular_units.h"

namespace shadesim {

std::string to_string(SpecularUnitKind kind) { return specular_unit(kind).name; }

SpecularUnitKind parse_specular_unit(const std::string& name, const std::string& what) {
  if (const SpecularUnitDescriptor* u = find_specular_unit(name)) return u->kind;
  throw std::invalid_argument(what + ": unknown specular unit '" + name + "'; expected one of " +
                              specular_unit_names());
}

std::string to_string(LutIndex v) { return v == LutIndex::kTruncate ? "truncate" : "nearest"; }
std::string to_string(LutAddressing v) {
  return v == LutAddressing::kPerExponent ? "per-exponent" : "shared";
}
std::string to_string(FitObjective v) {
  switch (v) {
    case FitObjective::kNone:
      return "none";
    case FitObjective::kEpicentre:
      return "epicentre";
    case FitObjective::kAbsolute:
      return "absolute";
  }
  return "?";
}
std::string to_string(UnitTiming v) {
  return v == UnitTiming::kPipelined ? "pipelined" : "iterative";
}

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

int SpecularConfig::series_per_light() const { return specular_unit(kind).series_per_light; }

void SpecularConfig::validate() const {
  auto fail = [](const std::string& field, const std::string& msg) {
    throw std::invalid_argument("specular config: " + field + " " + msg);
  };
  out.validate("specular config: out");
  if (out.is_signed || out.iwl < 1) fail("out", "must be unsigned with an integer bit (holds 1.0)");
  const SpecularUnitDescriptor& unit = specular_unit(kind);
  for (const SpecularField& f : unit.fields) {
    const int v = f.get(*this);
    if (!f.in_range(v))
      fail(unit.field_name(f), "must be " + f.expected() + ", got " + f.text(*this));
  }
  if (unit.check != nullptr) {
    try {
      unit.check(*this);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("specular config: ") + e.what());
    }
  }
}

std::string SpecularConfig::describe() const {
  const SpecularUnitDescriptor& unit = specular_unit(kind);
  return unit.name + unit.describe(*this);
}

}  // namespace shadesim
