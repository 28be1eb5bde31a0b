#include "model/specular_unit.h"

#include <cmath>
#include <stdexcept>

namespace shadesim {

SpecularUnit::SpecularUnit(const UnitConfig& config)
    : kind_(config.specular.kind), ideal_(config.series, config.specular.out) {
  config.specular.validate();
  const SpecularConfig& s = config.specular;
  switch (kind_) {
    case SpecularUnitKind::kLut:
      lut_.emplace(s.lut, config.series, s.out, config.material_buffers);
      break;
    case SpecularUnitKind::kSchlick:
      schlick_.emplace(s.schlick, config.series, s.out);
      break;
    case SpecularUnitKind::kWpow:
      wpow_.emplace(s.wpow, config.series, s.out);
      break;
    case SpecularUnitKind::kIdeal:
    case SpecularUnitKind::kNone:
      break;
  }
}

void SpecularUnit::load_material(const MaterialCmd& m) {
  ideal_.set_exponent(std::ldexp(static_cast<double>(m.exponent), -kExponentFracBits));
  if (lut_) {
    lut_->next_material();
    lut_->load_params(m.unit_params);
  }
  if (schlick_) schlick_->load_params(m.unit_params);
  if (wpow_) wpow_->load_params(m.unit_params);
}

void SpecularUnit::load_table(const TableCmd& t) {
  // Only the LUT has a table; for the other units a TABLE command is legal and ignored.
  if (lut_) lut_->load_table(t);
}

}  // namespace shadesim
