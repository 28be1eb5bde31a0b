// ShadeUnit: the bit-accurate model of the whole shading unit (rtl/shade_unit.sv). It consumes
// the command stream and emits one output pixel per span pixel, in stream order.
//
// Per SPAN: SpanSetup forms (v, d, d2) for every series of the current triangle; then per pixel
// SpecularUnit and PixelCombine read the series values, and every SeriesEngine steps.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "model/command_stream.h"
#include "model/pixel_combine.h"
#include "model/series_engine.h"
#include "model/span_setup.h"
#include "model/specular_unit.h"
#include "model/unit_config.h"

namespace shadesim {

struct PixelOut {
  uint16_t x = 0, y = 0;
  std::array<uint16_t, kMaxChannels> colour{};
  bool end_of_row = false;  // last pixel of a span marked last_in_row
};

class ShadeUnit {
 public:
  explicit ShadeUnit(const UnitConfig& config);

  // Feeds one command; calls sink(const PixelOut&) for each pixel a SPAN produces.
  template <typename Sink>
  void consume(const Command& cmd, Sink&& sink);

  // Convenience: run a whole stream and collect the pixels.
  std::vector<PixelOut> run(const CommandStream& stream);

  const UnitConfig& config() const { return config_; }

 private:
  void load_material(const MaterialCmd& m);

  UnitConfig config_;
  SpanSetup span_setup_;
  SpecularUnit specular_;
  PixelCombine combine_;
  SeriesBank series_;  // diffuse (l-major, c-minor) then specular per light
  std::vector<int64_t> ambient_;
  std::vector<int64_t> spec_colour_;
  TriangleCmd triangle_;
  bool have_material_ = false;
  bool have_triangle_ = false;
  std::vector<int64_t> spec_;  // scratch: specular intensity per light
};

template <typename Sink>
void ShadeUnit::consume(const Command& cmd, Sink&& sink) {
  if (const auto* s = std::get_if<SpanCmd>(&cmd)) {
    if (!have_triangle_ || !have_material_) {
      throw CommandStreamError("span before any tri/material command");
    }
    const int32_t dx = s->x0 - triangle_.xo;
    const int32_t dy = s->y - triangle_.yo;
    for (int i = 0; i < series_.size(); ++i) {
      series_.load(i, span_setup_(&triangle_.coef[static_cast<size_t>(i) * kTermsPerSeries], dx, dy));
    }
    const int diffuse = config_.diffuse_series();
    const int per_light = config_.specular.series_per_light();
    PixelOut px;
    px.y = static_cast<uint16_t>(s->y);
    for (int32_t k = 0; k < s->length; ++k) {
      const int64_t* values = series_.values();
      for (int l = 0; l < config_.lights; ++l) {
        spec_[l] = specular_.evaluate(&values[diffuse + l * per_light]);
      }
      px.x = static_cast<uint16_t>(s->x0 + k);
      px.colour = combine_(values, spec_.data(), ambient_.data(), spec_colour_.data());
      px.end_of_row = s->last_in_row && k == s->length - 1;
      sink(static_cast<const PixelOut&>(px));
      series_.step();
    }
  } else if (const auto* t = std::get_if<TriangleCmd>(&cmd)) {
    triangle_ = *t;
    have_triangle_ = true;
  } else if (const auto* m = std::get_if<MaterialCmd>(&cmd)) {
    load_material(*m);
  } else if (const auto* tb = std::get_if<TableCmd>(&cmd)) {
    specular_.load_table(*tb);
  }
}

}  // namespace shadesim
