#include "model/specular_config.h"

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

}  // namespace shadesim
