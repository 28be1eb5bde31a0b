// SpecularUnit: the specular slot of the shading unit — whichever unit the configuration
// selects, behind one interface. Per material it is loaded from MATERIAL (exponent, unit
// parameters) and TABLE commands; per pixel it maps the light's specular series values to an
// intensity in the specular output format.
//
// The host pre-scales the specular series per material for the selected unit
// (host/specular_setup.h: plan_specular gives the affine map of t, the unit_params words and the
// TABLE commands).
#pragma once

#include <cstdint>
#include <optional>

#include "model/command_stream.h"
#include "model/exponent_lut.h"
#include "model/schlick_divider.h"
#include "model/specular_ideal.h"
#include "model/unit_config.h"
#include "model/wpow_unit.h"

namespace shadesim {

class SpecularUnit {
 public:
  // Throws std::invalid_argument when config.specular does not validate.
  explicit SpecularUnit(const UnitConfig& config);

  void load_material(const MaterialCmd& m);
  void load_table(const TableCmd& t);

  // series[0 .. series_per_light-1]: this light's specular series values (series format raw).
  // Kind none reads none and gives 0.
  int64_t evaluate(const int64_t* series) const {
    switch (kind_) {
      case SpecularUnitKind::kLut:
        return lut_->evaluate(series[0]);
      case SpecularUnitKind::kSchlick:
        return schlick_->evaluate(series[0], series[1]);
      case SpecularUnitKind::kWpow:
        return wpow_->evaluate(series[0]);
      case SpecularUnitKind::kNone:
        return 0;  // no unit and no series (ShadeUnit does not call it)
      case SpecularUnitKind::kIdeal:
      default:
        return ideal_(series[0]);
    }
  }

  // The LUT when the kind is kLut (for write_hex), else nullptr.
  const ExponentLut* lut() const { return lut_ ? &*lut_ : nullptr; }

 private:
  SpecularUnitKind kind_;
  SpecularIdeal ideal_;
  std::optional<ExponentLut> lut_;
  std::optional<SchlickDivider> schlick_;
  std::optional<WpowUnit> wpow_;
};

}  // namespace shadesim
