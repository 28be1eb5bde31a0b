// ShadeUnit: the bit-accurate model of the whole shading unit (rtl/shade_unit.sv). It consumes
// the command stream and emits one output pixel per span pixel, in stream order.
//
// Per SPAN: SpanSetup forms (v, d, d2) for every series of the current triangle (with host span
// setup, UnitConfig::span_setup kHost, StartBank reads them from the SPAN instead); LaneFanout
// forms each lane's start from them (UnitConfig::lanes; one lane: unchanged); then per beat of
// `lanes` pixels SpecularUnit and PixelCombine read each valid lane's series values, in lane
// order, and every lane's SeriesEngines step. Every lane's specular slot holds the same
// material and table, so one SpecularUnit serves them all.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "model/command_stream.h"
#include "model/lane_fanout.h"
#include "model/pixel_combine.h"
#include "model/series_engine.h"
#include "model/span_setup.h"
#include "model/specular_unit.h"
#include "model/start_bank.h"
#include "model/unit_config.h"

namespace shadesim {

struct PixelOut {
  uint16_t x = 0, y = 0;
  std::array<uint16_t, kMaxChannels> colour{};
  bool end_of_row = false;  // last pixel of a span marked last_in_row
  int lane = 0;             // the lane of its beat (its index in the span mod UnitConfig::lanes)
  uint8_t spec_gates = 0;   // bit l: light l's specular gate was open (PixelCombine::gate)
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
  StartBank start_bank_;  // host span setup
  SpecularUnit specular_;
  PixelCombine combine_;
  LaneFanout fanout_;
  std::vector<SeriesBank> lanes_;  // per lane: diffuse (l-major, c-minor) then specular per light
  std::vector<int64_t> ambient_;
  std::vector<int64_t> spec_colour_;
  std::vector<int64_t> diffuse_colour_;  // diffuse colour multiply only
  uint32_t gate_only_ = 0;               // the MATERIAL's gate-only light mask
  TriangleCmd triangle_;
  bool have_material_ = false;
  bool have_triangle_ = false;
  std::vector<int64_t> spec_;  // scratch: specular intensity per light
};

template <typename Sink>
void ShadeUnit::consume(const Command& cmd, Sink&& sink) {
  if (const auto* s = std::get_if<SpanCmd>(&cmd)) {
    const bool host = config_.host_setup();
    if ((!host && !have_triangle_) || !have_material_) {
      throw CommandStreamError(host ? "span before any material command"
                                    : "span before any tri/material command");
    }
    if (host && s->starts.size() != static_cast<size_t>(StartLayout::of(config_).values)) {
      throw CommandStreamError("span: host span setup needs its start values");
    }
    const int32_t dx = s->x0 - triangle_.xo;
    const int32_t dy = s->y - triangle_.yo;
    const int n_lanes = fanout_.lanes();
    const int n_series = lanes_.front().size();
    for (int i = 0; i < n_series; ++i) {
      const SeriesStart start =
          host ? start_bank_(s->starts, i)
               : span_setup_(&triangle_.coef[static_cast<size_t>(i) * kTermsPerSeries], dx, dy);
      if (n_lanes == 1) {
        lanes_.front().load(i, start);
      } else {
        for (int j = 0; j < n_lanes; ++j) lanes_[static_cast<size_t>(j)].load(i, fanout_(start, j));
      }
    }
    const int diffuse = config_.diffuse_series();
    const int per_light = config_.specular.series_per_light();
    PixelOut px;
    px.y = static_cast<uint16_t>(s->y);
    // Pixel k of the span, on `lane` of its beat, from that lane's series values.
    auto shade = [&](const int64_t* values, int32_t k, int lane) {
      // Kind none (no specular series): spec_ stays 0, and PixelCombine adds no specular term.
      px.spec_gates = 0;
      for (int l = 0; per_light > 0 && l < config_.lights; ++l) {
        spec_[l] = specular_.evaluate(&values[diffuse + l * per_light]);
        px.spec_gates |= static_cast<uint8_t>(combine_.gate(values, l) ? 1u << l : 0u);
      }
      px.x = static_cast<uint16_t>(s->x0 + k);
      px.lane = lane;
      px.colour = combine_(values, spec_.data(), ambient_.data(), spec_colour_.data(),
                           diffuse_colour_.data(), gate_only_);
      px.end_of_row = s->last_in_row && k == s->length - 1;
      sink(static_cast<const PixelOut&>(px));
    };
    if (n_lanes == 1) {
      SeriesBank& bank = lanes_.front();
      for (int32_t k = 0; k < s->length; ++k) {
        shade(bank.values(), k, 0);
        bank.step();
      }
    } else {
      for (int32_t first = 0; first < s->length; first += n_lanes) {
        const int valid = std::min<int32_t>(n_lanes, s->length - first);
        for (int j = 0; j < valid; ++j)
          shade(lanes_[static_cast<size_t>(j)].values(), first + j, j);
        for (SeriesBank& bank : lanes_) bank.step();
      }
    }
  } else if (const auto* t = std::get_if<TriangleCmd>(&cmd)) {
    if (config_.host_setup())
      throw CommandStreamError("tri: a unit with host span setup takes no TRIANGLE");
    triangle_ = *t;
    have_triangle_ = true;
  } else if (const auto* m = std::get_if<MaterialCmd>(&cmd)) {
    load_material(*m);
  } else if (const auto* tb = std::get_if<TableCmd>(&cmd)) {
    specular_.load_table(*tb);
  }
}

}  // namespace shadesim
