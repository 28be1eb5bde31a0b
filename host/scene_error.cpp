#include "host/scene_error.h"

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
  const CycleEstimateRun run =
      CycleEstimate(CycleConfig::of(config)).run(frame.encode(config).stream.encode());
  return {run.cycles, run.pixels};
}

}  // namespace shadesim
