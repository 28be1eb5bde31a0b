#include "model/shade_unit.h"

namespace shadesim {
namespace {

// Validated before any member is sized from it (lanes_ has config.lanes banks).
const UnitConfig& validated(const UnitConfig& config) {
  config.validate();
  return config;
}

}  // namespace

ShadeUnit::ShadeUnit(const UnitConfig& config)
    : config_(validated(config)),
      span_setup_(config.coef, config.series, config.offset_bits),
      specular_(config),
      combine_(config),
      fanout_(config.series, config.lanes),
      lanes_(static_cast<size_t>(config.lanes),
             SeriesBank(config.series, config.series_per_triangle())),
      ambient_(static_cast<size_t>(config.channels), 0),
      spec_colour_(static_cast<size_t>(config.colours()), 0),
      diffuse_colour_(static_cast<size_t>(config.colours()), 0),
      spec_(static_cast<size_t>(config.lights), 0) {}

void ShadeUnit::load_material(const MaterialCmd& m) {
  ambient_ = m.ambient;
  spec_colour_ = m.spec_colour;
  if (config_.diffuse_multiply()) diffuse_colour_ = m.diffuse_colour;
  gate_only_ = m.gate_only;
  specular_.load_material(m);
  have_material_ = true;
}

std::vector<PixelOut> ShadeUnit::run(const CommandStream& stream) {
  std::vector<PixelOut> pixels;
  for (const auto& cmd : stream.commands) {
    consume(cmd, [&pixels](const PixelOut& p) { pixels.push_back(p); });
  }
  return pixels;
}

}  // namespace shadesim
