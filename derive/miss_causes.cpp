#include "derive/miss_causes.h"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "derive/accuracy_checks.h"
#include "derive/budget.h"
#include "derive/trial_unit.h"
#include "host/reference.h"
#include "host/scene_error.h"
#include "model/shade_unit.h"
#include "model/specular_units.h"

namespace shadesim {
namespace {

// The error of the scene on `unit`, in output codes.
int code_error(const PreparedScene& frame, const UnitConfig& unit) {
  return scene_error(frame, unit).max_code_lsb;
}

// The formats that alone bring `base` within `allowed` when widened to `lossless`'s, each
// re-shaded; "" when none alone does.
std::string formats_that_hold(const PreparedScene& frame, const UnitConfig& base,
                              const UnitConfig& lossless, int allowed) {
  struct Trial {
    const char* name;
    UnitConfig unit;
  };
  std::vector<Trial> trials;
  UnitConfig series = base;
  series.series = lossless.series;
  series.coef = lossless.coef;
  series.coef_term_iwl.clear();
  trials.push_back({"series and coef", series});
  UnitConfig colour = base;
  colour.spec_colour = lossless.spec_colour;
  trials.push_back({"spec_colour", colour});
  UnitConfig out = base;
  out.specular.out = lossless.specular.out;
  trials.push_back({"the specular output", out});
  std::string held;
  for (const Trial& t : trials) {
    const int e = code_error(frame, t.unit);
    if (e <= allowed)
      held += fmt::format("{}{} lossless: {} LSB", held.empty() ? "" : "; ", t.name, e);
  }
  return held;
}

std::string held_text(const std::string& held) {
  return held.empty() ? "no one format alone holds it; together they do" : held;
}

// The frame prepared again `kDeeperSubdivision` levels deeper (at most kDeepestSubdivision);
// nullptr where the frame is at that limit already.
std::unique_ptr<PreparedScene> deeper_frame(const PreparedScene& frame) {
  PrepareKey key = frame.key();
  const int deeper = std::min(kDeepestSubdivision, key.max_depth + kDeeperSubdivision);
  if (deeper <= key.max_depth) return nullptr;
  key.max_depth = deeper;
  return std::make_unique<PreparedScene>(frame.path(), key);
}

// Where neither the unit nor the formats explain a miss: deeper subdivision, then the gate, each
// on `lossless` (exact pow, formats that lose nothing: e_lossless codes off), else unknown.
MissExplanation geometry_cause(const PreparedScene& frame, const UnitConfig& lossless,
                               int e_lossless, int allowed, const std::string& exact_text,
                               const std::string& head) {
  const int max_depth = frame.key().max_depth;
  const SetupStats& setup = frame.setup().stats;
  std::string deeper_text =
      fmt::format("setup is at its deepest (--max-depth {})", kDeepestSubdivision);
  MissExplanation out;
  auto named = [&](MissCause cause, int e, const std::string& why) {
    out.cause = cause;
    out.error_removed = e;
    out.text = head + why;
    return out;
  };
  int least = e_lossless;
  if (const auto deep = deeper_frame(frame)) {
    const int e_deep = code_error(*deep, lossless);
    least = std::min(least, e_deep);
    if (e_deep <= allowed) {
      return named(MissCause::kTaylorSetup, e_deep,
                   fmt::format("the Taylor setup: {} triangle(s) over the budget at --max-depth "
                               "{} (worst {:.3g} LSB); prepared again at --max-depth {}, on "
                               "formats that lose nothing{} it is {} LSB",
                               setup.over_budget, max_depth, setup.worst_error_lsb,
                               deep->key().max_depth, exact_text, e_deep));
    }
    deeper_text = fmt::format("at --max-depth {} it is {} LSB", deep->key().max_depth, e_deep);
  }
  const int e_gate = error_against_taylor_gate(frame, lossless);
  least = std::min(least, e_gate);
  if (e_gate <= allowed) {
    return named(MissCause::kGate, e_gate,
                 fmt::format("the N.L gate near the terminator: on formats that lose nothing{} it "
                             "is still {} LSB, and against a reference gated by the Taylor "
                             "series' N.L as the unit gates (the exact N.L has the other sign "
                             "there) {} LSB; {}",
                             exact_text, e_lossless, e_gate, deeper_text));
  }
  out.cause = MissCause::kUnknown;
  out.error_removed = least;
  out.text = head + fmt::format(
                        "the cause is unknown: on formats that lose nothing{} it is still {} LSB; "
                        "{} ({} triangle(s) over the budget at --max-depth {}); against a "
                        "reference gated as the unit gates it is {} LSB",
                        exact_text, e_lossless, deeper_text, setup.over_budget, max_depth, e_gate);
  return out;
}

}  // namespace

const char* to_string(MissCause cause) {
  switch (cause) {
    case MissCause::kSpecularUnit:
      return "specular_unit";
    case MissCause::kFormats:
      return "formats";
    case MissCause::kUnitAndFormats:
      return "unit_and_formats";
    case MissCause::kTaylorSetup:
      return "taylor_setup";
    case MissCause::kGate:
      return "gate";
    case MissCause::kUnknown:
      return "unknown";
  }
  return "unknown";
}

int error_against_taylor_gate(const PreparedScene& frame, const UnitConfig& unit) {
  ShadeUnit model(unit);
  std::vector<PixelOut> pixels;
  frame.encode_chunks(unit, [&](CommandStream&& chunk) {
    for (const Command& cmd : chunk.commands)
      model.consume(cmd, [&pixels](const PixelOut& p) { pixels.push_back(p); });
  });
  ShadingVariant gated;
  gated.gate_quadratics = &frame.setup().series;
  const Scene& scene = frame.scene();
  const ReferenceImage ref =
      render_variant(frame.setup().triangles, frame.visibility(), scene, unit.channels, gated);
  return compare_to_reference(pixels, ref.values, frame.visibility().owner, scene.width,
                              scene.height, unit.channels, unit.out_bits)
      .stats.max_code_lsb;
}

MissExplanation explain_miss_cause(const PreparedScene& frame, const UnitConfig& unit,
                                   const ErrorStats& error) {
  const ConfigMeasurements m = measure_scene_on(frame, unit);
  const int allowed = code_budget(m.budget_lsb);
  MissExplanation out;
  const std::string head = fmt::format(
      "max {} LSB over the {:g} LSB budget ({} in output codes; {} of "
      "{} pixels off by more than 1): ",
      error.max_code_lsb, m.budget_lsb, allowed, error.pixels_over_1lsb, error.pixels);
  auto named = [&](MissCause cause, int e, const std::string& why) {
    out.cause = cause;
    out.error_removed = e;
    out.text = head + why;
    return out;
  };
  const bool hardware = specular_unit(unit.specular.kind).hardware;
  UnitConfig exact = unit;
  int e_exact = error.max_code_lsb;
  if (hardware) {
    exact.specular.kind = SpecularUnitKind::kIdeal;
    e_exact = code_error(frame, exact);
    if (e_exact <= allowed) {
      return named(MissCause::kSpecularUnit, e_exact,
                   fmt::format("the specular unit ({}) approximates t^n too coarsely: exact pow "
                               "on the same formats is {} LSB (shadesim config searches the "
                               "unit's fields; shadesim spec-error shows its error curve)",
                               unit.specular.describe(), e_exact));
    }
  }
  const UnitConfig lossless = lossless_formats(exact, m.colour_max);
  const int e_lossless = code_error(frame, lossless);
  if (e_lossless <= allowed && !hardware) {
    return named(
        MissCause::kFormats, e_lossless,
        fmt::format("the unit's formats: on formats that lose nothing it is {} LSB ({})",
                    e_lossless, held_text(formats_that_hold(frame, unit, lossless, allowed))));
  }
  if (e_lossless <= allowed) {
    // Exact pow alone misses: is it the formats alone, with the unit kept?
    const UnitConfig unit_lossless = lossless_formats(unit, m.colour_max);
    const int e_unit = code_error(frame, unit_lossless);
    if (e_unit <= allowed) {
      return named(MissCause::kFormats, e_unit,
                   fmt::format("the unit's formats: on formats that lose nothing, with the {} "
                               "unit kept, it is {} LSB ({})",
                               to_string(unit.specular.kind), e_unit,
                               held_text(formats_that_hold(frame, unit, unit_lossless, allowed))));
    }
    const std::string held = formats_that_hold(frame, exact, lossless, allowed);
    return named(
        MissCause::kUnitAndFormats, e_lossless,
        fmt::format("two causes that add up, the specular unit ({}) and the formats: exact pow on "
                    "the same formats is {} LSB, the unit on formats that lose nothing {} LSB, "
                    "and exact pow on formats that lose nothing {} LSB ({}; shadesim config "
                    "widens the format and searches the units again)",
                    unit.specular.describe(), e_exact, e_unit, e_lossless, held_text(held)));
  }
  // Neither the unit nor the formats: the frame's geometry.
  return geometry_cause(frame, lossless, e_lossless, allowed, hardware ? " with exact pow" : "",
                        head);
}

}  // namespace shadesim
