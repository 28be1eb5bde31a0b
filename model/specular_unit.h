// SpecularUnit: the specular slot of the shading unit — whichever unit the configuration
// selects, behind one interface. Per material it is loaded from MATERIAL (exponent, unit
// parameters) and TABLE commands; per pixel it maps the light's specular series values to an
// intensity in the specular output format.
#pragma once

#include <cstdint>

#include "model/command_stream.h"
#include "model/specular_ideal.h"
#include "model/unit_config.h"

namespace shadesim {

class SpecularUnit {
 public:
  explicit SpecularUnit(const UnitConfig& config);

  void load_material(const MaterialCmd& m);
  void load_table(const TableCmd& t);

  // series[0 .. series_per_light-1]: this light's specular series values (series format raw).
  int64_t evaluate(const int64_t* series) const {
    switch (kind_) {
      case SpecularUnitKind::kIdeal:
      default:
        return ideal_(series[0]);
    }
  }

 private:
  SpecularUnitKind kind_;
  SpecularIdeal ideal_;
};

}  // namespace shadesim
