#include "host/scene_error.h"

#include <variant>

#include "model/cycle_estimate.h"
#include "model/shade_unit.h"

namespace shadesim {

ErrorStats scene_error(const PreparedScene& frame, const UnitConfig& config) {
  return frame.error_on(config, [&] {
    // Shaded as it is encoded: the frame's whole stream is never held.
    ShadeUnit unit(config);
    std::vector<PixelOut> pixels;
    frame.encode_chunks(config, [&](CommandStream&& chunk) {
      for (const Command& cmd : chunk.commands)
        unit.consume(cmd, [&pixels](const PixelOut& p) { pixels.push_back(p); });
    });
    const ReferenceImage& ref = frame.reference(config.channels);
    const Scene& scene = frame.scene();
    return compare_to_reference(pixels, ref.values, frame.visibility().owner, scene.width,
                                scene.height, config.channels, config.out_bits)
        .stats;
  });
}

SceneCycles scene_cycles(const PreparedScene& frame, const UnitConfig& config) {
  const CommandStream stream = frame.encode(config).stream;
  const CycleEstimateRun run = CycleEstimate(CycleConfig::of(config)).run(stream.encode());
  return {run.cycles, run.pixels, pixel_beats(stream, config.lanes)};
}

uint64_t pixel_beats(const CommandStream& stream, int lanes) {
  uint64_t beats = 0;
  for (const Command& cmd : stream.commands) {
    if (const auto* span = std::get_if<SpanCmd>(&cmd))
      beats +=
          CycleEstimate::beats(static_cast<uint64_t>(span->length), static_cast<uint64_t>(lanes));
  }
  return beats;
}

}  // namespace shadesim
