#include "derive/format_widening.h"

#include <algorithm>
#include <array>
#include <functional>

#include "host/gate_flips.h"
#include "host/scene_error.h"
#include "model/specular_units.h"

namespace shadesim {
namespace {

// The widest fraction bits the colour and output formats take: lossless_formats'
// (derive/accuracy_checks.h).
constexpr int kLosslessFrac = 24;
// Series and coef: with_more_fraction_bits stops at UnitConfig's limits.
constexpr int kMostSeriesBits = 60;

int max_code_error(const FrameSet& frames, const UnitConfig& unit) {
  int worst = 0;
  for (size_t i = 0; i < frames.size(); ++i)
    worst = std::max(worst, scene_error(frames.at(i), unit).max_code_lsb);
  return worst;
}

// The fewest bits in [1, most] for which `holds` is true, assuming more bits hold no worse
// (doubling, then halving the interval: a handful of shadings); 0 where `most` does not hold.
int fewest_bits(int most, const std::function<bool(int)>& holds) {
  if (most < 1 || !holds(most)) return 0;
  int lo = 0, hi = 1;
  while (hi < most && !holds(hi)) lo = hi, hi = std::min(2 * hi, most);
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (holds(mid) ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace

std::string FormatWidening::describe() const {
  std::string s;
  auto add = [&s](const char* name, int bits) {
    if (bits > 0) s += (s.empty() ? "" : ", ") + std::string(name) + " +" + std::to_string(bits);
  };
  add("spec_colour", spec_colour);
  add("specular out", specular_out);
  add("series and coef", series_coef);
  return s + " fraction bits";
}

UnitConfig widened(const UnitConfig& unit, const FormatWidening& w) {
  UnitConfig u = w.series_coef > 0 ? with_more_fraction_bits(unit, w.series_coef) : unit;
  u.spec_colour.wl += w.spec_colour;
  u.specular.out.wl += w.specular_out;
  u.validate();
  return u;
}

std::optional<FormatWidening> widening_that_holds(const FrameSet& frames, const UnitConfig& unit,
                                                  int allowed) {
  UnitConfig exact = unit;
  if (specular_unit(unit.specular.kind).hardware) exact.specular.kind = SpecularUnitKind::kIdeal;
  const std::array<int, 3> most = {
      std::max(0, kLosslessFrac - exact.spec_colour.frac_bits()),
      exact.specular.kind == SpecularUnitKind::kNone
          ? 0
          : std::max(0, kLosslessFrac - exact.specular.out.frac_bits()),
      kMostSeriesBits};
  auto as_widening = [](const std::array<int, 3>& bits) {
    FormatWidening w;
    w.spec_colour = bits[0];
    w.specular_out = bits[1];
    w.series_coef = bits[2];
    return w;
  };
  auto error_with = [&](const std::array<int, 3>& bits) {
    return max_code_error(frames, widened(exact, as_widening(bits)));
  };
  const int before = max_code_error(frames, exact);
  if (before <= allowed || error_with(most) > allowed) return std::nullopt;
  std::optional<std::array<int, 3>> best;
  for (size_t f = 0; f < most.size(); ++f) {
    const int bits = fewest_bits(most[f], [&](int b) {
      std::array<int, 3> one{};
      one[f] = b;
      return error_with(one) <= allowed;
    });
    if (bits == 0) continue;
    std::array<int, 3> one{};
    one[f] = bits;
    if (!best || bits < std::max({(*best)[0], (*best)[1], (*best)[2]})) best = one;
  }
  if (!best) {
    const int bits = fewest_bits(kMostSeriesBits, [&](int b) {
      return error_with({std::min(b, most[0]), std::min(b, most[1]), std::min(b, most[2])}) <=
             allowed;
    });
    best = std::array<int, 3>{std::min(bits, most[0]), std::min(bits, most[1]),
                              std::min(bits, most[2])};
  }
  FormatWidening w = as_widening(*best);
  w.exact_before = before;
  w.exact_after = error_with(*best);
  return w;
}

}  // namespace shadesim
