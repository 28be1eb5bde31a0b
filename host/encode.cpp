#include "host/encode.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <utility>
#include <vector>

#include "host/specular_setup.h"
#include "model/host_setup.h"

namespace shadesim {
namespace {

double channel(const Vec3& v, int c) { return c == 0 ? v.x : (c == 1 ? v.y : v.z); }

class CoefficientWriter {
 public:
  CoefficientWriter(const UnitConfig& config, EncodeStats& stats)
      : coef_wl_(config.coef.wl), stats_(stats) {
    for (int k = 0; k < kTermsPerSeries; ++k) {
      const FixedFormat& term = terms_[static_cast<size_t>(k)] = config.coef_term(k);
      const double lsb = std::ldexp(1.0, -term.frac_bits());
      in_range_[static_cast<size_t>(k)] = {(term.raw_min() - 0.5) * lsb,
                                           (term.raw_max() + 0.5) * lsb};
    }
  }

  // Appends a*q + b (q about the origin pixel's centre) as T0..T5, each in its term's format.
  void append(const Quadratic& q, double a, double b, std::vector<int64_t>& out) const {
    for (int k = 0; k < kTermsPerSeries; ++k) {
      const FixedFormat& term = terms_[static_cast<size_t>(k)];
      const double value = a * q.t[k] + (k == 0 ? b : 0.0);
      if (!std::isfinite(value)) throw std::runtime_error("encoder: non-finite Taylor coefficient");
      const auto& [lo, hi] = in_range_[static_cast<size_t>(k)];
      if (value >= hi || value < lo) {
        // A term narrower than coef saturates; one in coef's own format follows coef's rule.
        ++(term.wl < coef_wl_ ? stats_.narrow_terms_saturated : stats_.coefficients_out_of_range);
      }
      out.push_back(term.from_double(value));
    }
  }

 private:
  std::array<FixedFormat, kTermsPerSeries> terms_;
  // Per term, the values that round into its range: [lo, hi).
  std::array<std::pair<double, double>, kTermsPerSeries> in_range_;
  int coef_wl_;
  EncodeStats& stats_;
};

// What light l's diffuse series of channel c is scaled by: kd_c L_c.
double diffuse_scale(const Scene& scene, const Material& m, int l, int c) {
  return channel(m.diffuse, c) * channel(scene.lights[static_cast<size_t>(l)].colour, c);
}

MaterialCmd material_command(const Scene& scene, const UnitConfig& config, const Material& m,
                             const SpecularSeriesPlan& plan) {
  MaterialCmd cmd;
  for (int c = 0; c < config.channels; ++c) {
    cmd.ambient.push_back(
        config.series.from_double(channel(m.ambient, c) * channel(scene.ambient_light, c)));
  }
  for (int l = 0; l < config.lights; ++l) {
    for (int c = 0; c < config.channels; ++c) {
      const bool present = l < static_cast<int>(scene.lights.size());
      cmd.spec_colour.push_back(config.spec_colour.from_double(
          present ? channel(m.specular, c) * channel(scene.lights[static_cast<size_t>(l)].colour, c)
                  : 0.0));
    }
  }
  cmd.exponent = kExponentFormat.from_double(m.exponent);
  cmd.unit_params = plan.unit_params;
  if (config.diffuse_multiply()) {
    // The colour the unit multiplies each light's N.L series by; that series gates its light.
    for (int l = 0; l < config.lights; ++l) {
      for (int c = 0; c < config.channels; ++c) {
        const bool present = l < static_cast<int>(scene.lights.size());
        cmd.diffuse_colour.push_back(
            config.spec_colour.from_double(present ? diffuse_scale(scene, m, l, c) : 0.0));
      }
    }
    return cmd;
  }
  // The specular gate reads light l's diffuse series (model/pixel_combine.h): a light with a
  // specular colour and no diffuse colour gets channel 0's series unscaled, gate only.
  for (int l = 0; l < config.lights && l < static_cast<int>(scene.lights.size()); ++l) {
    bool diffuse = false, specular = false;
    for (int c = 0; c < config.channels; ++c) {
      diffuse = diffuse || diffuse_scale(scene, m, l, c) > 0;
      specular = specular || cmd.spec_colour[static_cast<size_t>(l) * config.channels + c] != 0;
    }
    if (specular && !diffuse) cmd.gate_only |= 1u << l;
  }
  return cmd;
}

struct Pixel {
  int32_t x = 0, y = 0;
};

// Spans [begin, end) of one triangle from one origin.
struct OriginGroup {
  size_t end = 0;
  Pixel origin;
};

// The longest run of spans from `begin` (before `end`) whose starts lie within one offset range
// of offset_bits signed bits, and its origin: the triangle's centroid pixel moved, per axis, just
// far enough that every start's offset fits. A triangle that fits keeps the centroid pixel.
OriginGroup next_origin_group(const std::vector<Span>& spans, size_t begin, size_t end,
                              Pixel centroid, int offset_bits) {
  const int32_t lo = -(int32_t{1} << (offset_bits - 1)), hi = -lo - 1;
  int32_t x_min = spans[begin].x0, x_max = x_min, y_min = spans[begin].y, y_max = y_min;
  size_t k = begin + 1;
  for (; k < end; ++k) {
    const Span& s = spans[k];
    const int32_t nx_min = std::min(x_min, s.x0), nx_max = std::max(x_max, s.x0);
    const int32_t ny_min = std::min(y_min, s.y), ny_max = std::max(y_max, s.y);
    if (nx_max - nx_min > hi - lo || ny_max - ny_min > hi - lo) break;
    x_min = nx_min, x_max = nx_max, y_min = ny_min, y_max = ny_max;
  }
  return {k,
          {std::clamp(centroid.x, x_max - hi, x_min - lo),
           std::clamp(centroid.y, y_max - hi, y_min - lo)}};
}

// One TRIANGLE: every series' quadratic re-expanded about the origin pixel's centre.
TriangleCmd triangle_command(const UnitConfig& config, int scene_lights,
                             const TriangleSeries& series, const Scene& scene,
                             const Material& material, uint32_t gate_only,
                             const SpecularSeriesPlan& plan, const CoefficientWriter& writer,
                             Pixel origin) {
  const Quadratic zero{};
  TriangleCmd t;
  t.coef.reserve(static_cast<size_t>(config.series_per_triangle()) * kTermsPerSeries);
  t.xo = origin.x;
  t.yo = origin.y;
  const double ox = t.xo + 0.5, oy = t.yo + 0.5;
  for (int l = 0; l < config.lights; ++l) {
    const bool present = l < scene_lights;
    const Quadratic q = present ? series.diffuse[static_cast<size_t>(l)].recentred(ox, oy) : zero;
    if (config.diffuse_multiply()) {  // N.L itself: the unit multiplies by the colour
      writer.append(q, 1.0, 0.0, t.coef);
      continue;
    }
    for (int c = 0; c < config.channels; ++c) {
      // A gate-only light: channel 0 carries N.L itself (its colour is 0 in every channel).
      double scale = 0.0;
      if (present) {
        scale =
            (gate_only >> l & 1) != 0 ? (c == 0 ? 1.0 : 0.0) : diffuse_scale(scene, material, l, c);
      }
      writer.append(q, scale, 0.0, t.coef);
    }
  }
  for (int l = 0; l < config.lights; ++l) {
    // An absent light's specular series still feeds the unit (its colour is 0): give it the
    // unit's value for t = 0 so it stays in the unit's input range.
    const Quadratic q =
        l < scene_lights ? series.specular[static_cast<size_t>(l)].recentred(ox, oy) : zero;
    for (const auto& [a, b] : plan.affine) writer.append(q, a, b, t.coef);
  }
  return t;
}

}  // namespace

UnitConfig config_for_scene(const Scene& scene, UnitConfig base) {
  base.channels = scene.is_grey() ? 1 : 3;
  base.lights = static_cast<int>(scene.lights.size());
  base.validate();
  return base;
}

void check_scene_fits(const Scene& scene, const UnitConfig& config) {
  if (static_cast<int>(scene.lights.size()) > config.lights) {
    throw std::invalid_argument(scene.path + ": scene has " + std::to_string(scene.lights.size()) +
                                " lights; the unit (" + config.to_string() + ") has series for " +
                                std::to_string(config.lights) +
                                ": it needs lights >= " + std::to_string(scene.lights.size()));
  }
  if (!scene.is_grey() && config.channels < 3) {
    throw std::invalid_argument(scene.path + ": scene has colour; the unit (" + config.to_string() +
                                ") has one channel: it needs channels = 3");
  }
}

namespace {

// Where encode_frame_chunks collects commands until a chunk is due.
class ChunkWriter {
 public:
  ChunkWriter(const UnitConfig& config, EncodeStats& stats, const ChunkSink& sink,
              size_t chunk_commands)
      : config_(config), stats_(stats), sink_(sink), chunk_commands_(chunk_commands) {
    chunk_.reserve(chunk_commands_ + 64);
  }
  std::vector<Command>& commands() { return chunk_; }
  // After a triangle's last span: the chunk goes when full. Chunks end only there, so a span
  // and its TRIANGLE always share one (host setup and validation read them together).
  void triangle_done() {
    if (chunk_.size() >= chunk_commands_) flush();
  }
  void flush() {
    CommandStream stream;
    stream.config = config_;
    stream.config.span_setup = SpanSetupSite::kUnit;
    stream.commands = std::move(chunk_);
    chunk_ = {};
    chunk_.reserve(chunk_commands_ + 64);
    // Host span setup: the same commands, each span's start values in place of the
    // coefficients.
    if (config_.host_setup()) stream = with_host_setup(std::move(stream));
    stream.config = config_;
    stats_.words += stream.word_count();
    stream.validate("encoder");
    sink_(std::move(stream));
  }

 private:
  const UnitConfig& config_;
  EncodeStats& stats_;
  const ChunkSink& sink_;
  size_t chunk_commands_;
  std::vector<Command> chunk_;
};

}  // namespace

EncodeStats encode_frame_chunks(const Scene& scene, const UnitConfig& config,
                                const SetupResult& setup, const Visibility& vis,
                                const ChunkSink& sink, size_t chunk_commands) {
  check_scene_fits(scene, config);
  const int scene_lights = static_cast<int>(scene.lights.size());
  EncodeStats stats;
  ChunkWriter out(config, stats, sink, std::max<size_t>(1, chunk_commands));
  const CoefficientWriter writer(config, stats);
  int current_material = -1;

  // The unit's specular series plan per material: affine pre-scaling of t, unit parameters, and
  // for a per-exponent LUT the table to load on every switch to that material.
  std::vector<SpecularSeriesPlan> plans;
  for (const auto& m : scene.materials) plans.push_back(plan_specular(config, m.exponent));
  std::vector<uint32_t> material_gate_only(scene.materials.size(), 0);  // each MATERIAL's mask
  // A shared table (no reload) is loaded once, before the first pixel.
  for (auto& t : shared_lut_tables(config)) {
    stats.table_words += t.entries.size();
    out.commands().emplace_back(std::move(t));
  }

  size_t i = 0;
  while (i < vis.spans.size()) {
    const uint32_t tri_index = vis.spans[i].triangle;
    if (tri_index >= setup.triangles.size())
      throw std::logic_error("encoder: span names an unknown triangle");
    const ScreenTriangle& tri = setup.triangles[tri_index];
    const TriangleSeries& series = setup.series[tri_index];
    const Material& material = scene.materials.at(static_cast<size_t>(tri.material));

    const SpecularSeriesPlan& plan = plans[static_cast<size_t>(tri.material)];
    if (tri.material != current_material) {
      MaterialCmd m = material_command(scene, config, material, plan);
      material_gate_only[static_cast<size_t>(tri.material)] = m.gate_only;
      out.commands().emplace_back(std::move(m));
      for (const auto& t : plan.tables) {
        stats.table_words += t.entries.size();
        out.commands().emplace_back(t);
      }
      stats.table_load_cycles += plan.load_cycles;
      current_material = tri.material;
      ++stats.materials;
    }

    // Origin: the pixel holding the centroid, clamped into the image. Integer offsets from it
    // keep span setup's products exact; the quadratic is re-expanded about that pixel's centre.
    // The clamp bounds the offsets (and so the coefficient error they multiply) by the image
    // size, however far off-screen a triangle reaches: a piece clipped at the near plane can
    // have its centroid thousands of pixels away, beyond the 16-bit origin field.
    const double xc = (tri.v[0].x + tri.v[1].x + tri.v[2].x) / 3.0;
    const double yc = (tri.v[0].y + tri.v[1].y + tri.v[2].y) / 3.0;
    const Pixel centroid{static_cast<int32_t>(std::clamp(std::floor(xc), 0.0, scene.width - 1.0)),
                         static_cast<int32_t>(std::clamp(std::floor(yc), 0.0, scene.height - 1.0))};
    size_t end = i;
    while (end < vis.spans.size() && vis.spans[end].triangle == tri_index) ++end;
    // Span setup takes offsets of offset_bits: spans beyond them from one origin go in groups,
    // each a TRIANGLE of its own about an origin its spans' starts reach (a re-origin).
    bool first_group = true;
    while (i < end) {
      const OriginGroup group = next_origin_group(vis.spans, i, end, centroid, config.offset_bits);
      if (!first_group) ++stats.reorigins;
      first_group = false;
      out.commands().emplace_back(triangle_command(
          config, scene_lights, series, scene, material,
          material_gate_only[static_cast<size_t>(tri.material)], plan, writer, group.origin));
      ++stats.triangles;
      for (; i < group.end; ++i) {
        const Span& s = vis.spans[i];
        out.commands().emplace_back(SpanCmd{s.y, s.x0, s.length, s.last_in_row, {}});
        ++stats.spans;
        stats.pixels += static_cast<size_t>(s.length);
      }
    }
    out.triangle_done();
  }
  out.commands().emplace_back(EndFrameCmd{});
  out.flush();
  return stats;
}

EncodedFrame encode_frame(const Scene& scene, const UnitConfig& config, const SetupResult& setup,
                          const Visibility& vis) {
  EncodedFrame frame;
  frame.stream.config = config;
  auto& cmds = frame.stream.commands;
  // Every span, a TRIANGLE per triangle (more where one re-origins), the materials' switches:
  // reserved once, so a large frame's commands are not copied by doubling growth.
  cmds.reserve(vis.spans.size() + setup.triangles.size() + scene.materials.size() + 2);
  frame.stats = encode_frame_chunks(
      scene, config, setup, vis,
      [&cmds](CommandStream&& chunk) {
        std::move(chunk.commands.begin(), chunk.commands.end(), std::back_inserter(cmds));
      },
      kEncodeChunkCommands);
  return frame;
}

}  // namespace shadesim
