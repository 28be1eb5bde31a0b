#include "host/gate_flips.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <vector>

#include "host/encode.h"
#include "host/metrics.h"
#include "host/parallel.h"
#include "model/shade_unit.h"

namespace shadesim {
namespace {

// Every visible pixel's output codes and specular gates, indexed y * width + x.
struct ShadedFrame {
  std::vector<std::array<uint16_t, kMaxChannels>> colour;
  std::vector<uint8_t> gates;
  std::vector<bool> shaded;
  std::vector<PixelOut> pixels;  // in the unit's order, as scene_error compares them
};

// The unit-independent part of a frame.
struct Geometry {
  const Scene& scene;
  const SetupResult& setup;
  const Visibility& visibility;
};

ShadedFrame shade(const Geometry& frame, const UnitConfig& unit) {
  const int width = frame.scene.width;
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(frame.scene.height);
  ShadedFrame out{std::vector<std::array<uint16_t, kMaxChannels>>(n), std::vector<uint8_t>(n, 0),
                  std::vector<bool>(n, false)};
  ShadeUnit model(unit);
  const auto take = [&](const PixelOut& p) {
    out.pixels.push_back(p);
    const size_t at = static_cast<size_t>(p.y) * static_cast<size_t>(width) + p.x;
    out.colour[at] = p.colour;
    out.gates[at] = p.spec_gates;
    out.shaded[at] = true;
  };
  // Shaded as it is encoded: the frame's whole stream is never held.
  encode_frame_chunks(frame.scene, unit, frame.setup, frame.visibility, [&](CommandStream&& chunk) {
    for (const Command& cmd : chunk.commands) model.consume(cmd, take);
  });
  return out;
}

// Flips of `shaded` against `widest` more than `budget_codes` off.
GateFlips count_flips(const ShadedFrame& shaded, const ShadedFrame& widest, int channels,
                      int budget_codes) {
  GateFlips f;
  for (size_t i = 0; i < shaded.gates.size(); ++i) {
    if (!shaded.shaded[i] || shaded.gates[i] == widest.gates[i]) continue;
    int diff = 0;
    for (int c = 0; c < channels; ++c) {
      diff = std::max(diff, std::abs(int{shaded.colour[i][static_cast<size_t>(c)]} -
                                     int{widest.colour[i][static_cast<size_t>(c)]}));
    }
    if (diff <= budget_codes) continue;
    ++f.pixels;
    f.max_lsb = std::max(f.max_lsb, diff);
  }
  return f;
}

// The most fraction bits with_more_fraction_bits can add: FixedFormat's 62-bit words and 60
// fraction bits, and span setup's 120-bit intermediate (UnitConfig::validate).
int most_fraction_bits(const UnitConfig& u) {
  const int setup_room = 120 - 4 - 2 * (u.xy_bits + 2) - u.coef.wl;
  return std::max(0, std::min({62 - u.series.wl, 60 - u.series.frac_bits(), 62 - u.coef.wl,
                               60 - u.coef.frac_bits(), setup_room}));
}

}  // namespace

UnitConfig with_more_fraction_bits(const UnitConfig& unit, int bits) {
  UnitConfig u = unit;
  const int add = std::min(bits, most_fraction_bits(unit));
  u.series.wl += add;
  u.coef.wl += add;
  u.validate();
  return u;
}

namespace {

GateFlips measure_on(const Geometry& frame, const UnitConfig& unit, int budget_codes, int threads,
                     const std::function<void(const ShadedFrame&)>& on_unit) {
  const int most = most_fraction_bits(unit);
  // The yardstick and the unit are two independent shadings of the frame: side by side.
  const std::vector<UnitConfig> units = {with_more_fraction_bits(unit, most), unit};
  std::vector<ShadedFrame> both = parallel_map<ShadedFrame>(
      units.size(), threads, [&](size_t i) { return shade(frame, units[i]); });
  const ShadedFrame& widest = both[0];
  const ShadedFrame& shaded = both[1];
  if (on_unit) on_unit(shaded);
  GateFlips f = count_flips(shaded, widest, unit.channels, budget_codes);
  f.fixed = unit;
  if (f.pixels == 0) return f;
  auto holds = [&](int bits) {
    return count_flips(shade(frame, with_more_fraction_bits(unit, bits)), widest, unit.channels,
                       budget_codes)
               .pixels == 0;
  };
  // The fewest bits that hold: doubling to a width that holds, then halving the interval (a
  // handful of shadings of the frame, not one per bit).
  // Only short of the widest formats (the yardstick itself) is a width that holds meaningful.
  int lo = 0, hi = 1;
  while (hi < most && !holds(hi)) lo = hi, hi = std::min(2 * hi, most);
  if (hi >= most) {
    f.fix_bits = -1;
    return f;
  }
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (holds(mid) ? hi : lo) = mid;
  }
  f.fix_bits = hi;
  f.fixed = with_more_fraction_bits(unit, hi);
  return f;
}

}  // namespace

GateFlips measure_gate_flips(const Scene& scene, const SetupResult& setup,
                             const Visibility& visibility, const UnitConfig& unit,
                             int budget_codes) {
  return measure_on(Geometry{scene, setup, visibility}, unit, budget_codes, 1, nullptr);
}

GateFlips measure_gate_flips(const PreparedScene& frame, const UnitConfig& unit, int budget_codes,
                             int threads) {
  const Scene& scene = frame.scene();
  const auto record_error = [&](const ShadedFrame& shaded) {
    frame.error_on(unit, [&] {
      return compare_to_reference(shaded.pixels, frame.reference(unit.channels).values,
                                  frame.visibility().owner, scene.width, scene.height,
                                  unit.channels, unit.out_bits)
          .stats;
    });
  };
  return measure_on(Geometry{scene, frame.setup(), frame.visibility()}, unit, budget_codes, threads,
                    record_error);
}

}  // namespace shadesim
