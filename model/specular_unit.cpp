#include "model/specular_unit.h"

#include <cmath>
#include <stdexcept>

namespace shadesim {

SpecularUnit::SpecularUnit(const UnitConfig& config)
    : kind_(config.specular.kind), ideal_(config.series, config.specular.out) {
  if (kind_ != SpecularUnitKind::kIdeal) {
    throw std::invalid_argument("specular unit '" + to_string(kind_) +
                                "' is not available in this build of the model");
  }
}

void SpecularUnit::load_material(const MaterialCmd& m) {
  ideal_.set_exponent(std::ldexp(static_cast<double>(m.exponent), -kExponentFracBits));
}

void SpecularUnit::load_table(const TableCmd&) {
  // The ideal unit has no table; a TABLE command is legal and ignored.
}

}  // namespace shadesim
