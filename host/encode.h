// Encoder: from set-up triangles and visibility spans to the command stream the unit consumes.
// Here the per-triangle double quadratics become fixed-point words: colours are rolled into the
// diffuse series (so the per-pixel path has no multiplier), the specular series is pre-scaled
// for the unit, and each quadratic is re-expanded about an integer origin pixel.
#pragma once

#include <cstddef>
#include <functional>

#include "host/scene.h"
#include "host/screen.h"
#include "host/triangle_setup.h"
#include "model/command_stream.h"
#include "model/unit_config.h"

namespace shadesim {

// `base` with the structure the scene needs: one channel for a grey scene, one series set per
// light. Widths are kept.
UnitConfig config_for_scene(const Scene& scene, UnitConfig base);

struct EncodeStats {
  std::size_t materials = 0;  // MATERIAL commands (material switches, including the first)
  std::size_t triangles = 0;  // TRI commands: triangles that own at least one pixel
  // TRI commands beyond a triangle's first: its spans' starts did not all fit one origin's
  // UnitConfig::offset_bits, so later spans came from another origin (included in `triangles`).
  std::size_t reorigins = 0;
  std::size_t spans = 0;
  std::size_t pixels = 0;
  std::size_t words = 0;          // 64-bit words on the cmd port
  std::size_t table_words = 0;    // of which exponent-table entries
  int64_t table_load_cycles = 0;  // table reload cost of the material switches
  // Coefficients outside the coef format's range. With :wrap they are exact modulo 2^iwl and
  // harmless while pixel values stay in range; with :sat they are clipped and pixels are wrong.
  std::size_t coefficients_out_of_range = 0;
  // Coefficients that did not fit their term's narrowed format (UnitConfig::coef_term_iwl).
  std::size_t narrow_terms_saturated = 0;
};

struct EncodedFrame {
  CommandStream stream;
  EncodeStats stats;
};

// Throws std::invalid_argument naming what does not fit when a unit built for `config` cannot
// shade `scene`: it needs at least the scene's lights, and three channels unless the scene is grey.
void check_scene_fits(const Scene& scene, const UnitConfig& config);

// setup.triangles are the triangles vis.owner / vis.spans refer to. The unit may be larger than
// the scene needs (a fixed RTL configuration): lights beyond the scene's get all-zero series and
// colours, and a grey scene on an RGB unit repeats its one channel.
EncodedFrame encode_frame(const Scene& scene, const UnitConfig& config, const SetupResult& setup,
                          const Visibility& vis);

// The same frame a chunk at a time: each chunk a CommandStream on `config` (host setup applied,
// validated) of about `chunk_commands` commands, ending after a triangle's last span (the last
// one with END_FRAME). Concatenated, the chunks are encode_frame's stream, bit for bit; a
// consumer that shades, walks or counts them as they come never holds the whole frame. Returns
// the frame's stats.
using ChunkSink = std::function<void(CommandStream&&)>;
inline constexpr size_t kEncodeChunkCommands = 16384;
EncodeStats encode_frame_chunks(const Scene& scene, const UnitConfig& config,
                                const SetupResult& setup, const Visibility& vis,
                                const ChunkSink& sink,
                                size_t chunk_commands = kEncodeChunkCommands);

}  // namespace shadesim
