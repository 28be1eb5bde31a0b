// explore's knobs (explore/explore.h): the widths the error search narrows, and the structure it
// sweeps beside them for the table and the Pareto front (span setup site, start depth, diffuse
// colour, pipelining), whose pixels or cycles change but whose worth is area against clock.
#include <algorithm>

#include "derive/pipelining.h"
#include "explore/explore.h"
#include "model/specular_units.h"

namespace shadesim {

namespace {

std::vector<int> range_of(int lo, int hi) {
  std::vector<int> v;
  for (int i = lo; i <= hi; ++i) v.push_back(i);
  return v;
}

std::vector<std::string> numbers(const std::vector<int>& v) {
  std::vector<std::string> s;
  s.reserve(v.size());
  for (int x : v) s.push_back(std::to_string(x));
  return s;
}

Knob numeric(std::string stage, std::string name, int lo, int hi,
             std::function<void(UnitConfig&, int)> apply,
             std::function<int(const UnitConfig&)> read, bool searched = true) {
  Knob k;
  k.stage = std::move(stage);
  k.name = std::move(name);
  k.values = range_of(lo, std::max(lo, hi));
  k.labels = numbers(k.values);
  k.apply = std::move(apply);
  k.read = std::move(read);
  k.searched = searched;
  return k;
}

// Fraction bits of a format held in a UnitConfig member, keeping its integer bits.
Knob frac_knob(std::string stage, std::string name, FixedFormat UnitConfig::*member, int lo,
               int widen, const UnitConfig& start) {
  const FixedFormat& f = start.*member;
  const int hi = std::min(f.frac_bits() + widen, 62 - f.iwl);
  return numeric(
      std::move(stage), std::move(name), lo, hi,
      [member](UnitConfig& c, int v) { (c.*member).wl = (c.*member).iwl + v; },
      [member](const UnitConfig& c) { return (c.*member).frac_bits(); });
}

Knob int_knob(std::string stage, std::string name, FixedFormat UnitConfig::*member, int lo,
              int widen, const UnitConfig& start) {
  const FixedFormat& f = start.*member;
  const int hi = std::min(f.iwl + widen, 62 - f.frac_bits());
  return numeric(
      std::move(stage), std::move(name), lo, hi,
      [member](UnitConfig& c, int v) {
        FixedFormat& g = c.*member;
        const int frac = g.frac_bits();
        g.iwl = v;
        g.wl = v + frac;
      },
      [member](const UnitConfig& c) { return (c.*member).iwl; });
}

Knob choice(std::string stage, std::string name, std::vector<std::string> labels,
            std::function<void(UnitConfig&, int)> apply,
            std::function<int(const UnitConfig&)> read) {
  Knob k;
  k.stage = std::move(stage);
  k.name = std::move(name);
  for (std::size_t i = 0; i < labels.size(); ++i) k.values.push_back(static_cast<int>(i));
  k.labels = std::move(labels);
  k.apply = std::move(apply);
  k.read = std::move(read);
  k.choice = true;
  return k;
}

// The widths: coefficient and series integer and fraction bits, the series' rounding and
// overflow, the specular unit's output and fields, the specular colour's fraction bits.
void width_knobs(const UnitConfig& start, std::vector<Knob>& k) {
  const char* coef = "coefficients";
  const char* series = "series";
  const char* spec = "specular";
  k.push_back(int_knob(coef, "coef.int", &UnitConfig::coef, 2, 2, start));
  k.push_back(frac_knob(coef, "coef.frac", &UnitConfig::coef, 8, 4, start));
  k.push_back(int_knob(series, "series.int", &UnitConfig::series, 2, 2, start));
  k.push_back(frac_knob(series, "series.frac", &UnitConfig::series, start.out_bits, 4, start));
  k.push_back(choice(
      series, "series.quant", {"trn", "rnd"},
      [](UnitConfig& c, int v) {
        c.series.quant = v ? Quantization::kRoundNearest : Quantization::kTruncate;
      },
      [](const UnitConfig& c) { return c.series.quant == Quantization::kRoundNearest ? 1 : 0; }));
  k.push_back(choice(
      series, "series.overflow", {"wrap", "sat"},
      [](UnitConfig& c, int v) { c.series.overflow = v ? Overflow::kSaturate : Overflow::kWrap; },
      [](const UnitConfig& c) { return c.series.overflow == Overflow::kSaturate ? 1 : 0; }));
  const SpecularConfig& s = start.specular;
  // Specular kind none has no specular term: its output and colour widths reach no pixel and no
  // hardware, so they are not searched.
  const bool specular_term = s.kind != SpecularUnitKind::kNone;
  if (specular_term)
    k.push_back(numeric(
        spec, "spec.out.frac", 4, std::min(s.out.frac_bits() + 2, 60),
        [](UnitConfig& c, int v) { c.specular.out.wl = c.specular.out.iwl + v; },
        [](const UnitConfig& c) { return c.specular.out.frac_bits(); }));
  // The selected unit's explored fields (model/specular_units.h).
  const SpecularUnitDescriptor& unit = specular_unit(s.kind);
  for (const SpecularField& f : unit.fields) {
    if (f.explore_hi == nullptr) continue;
    const SpecularField* field = &f;  // the table outlives every knob
    k.push_back(numeric(
        spec, unit.field_name(f), f.explore_lo, f.explore_hi(f.get(s)),
        [field](UnitConfig& c, int v) { field->set(c.specular, v); },
        [field](const UnitConfig& c) { return field->get(c.specular); }));
  }
  if (specular_term)
    k.push_back(
        frac_knob("specular colour", "spec_colour.frac", &UnitConfig::spec_colour, 2, 2, start));
}

// Span setup in the unit or on the host, and the host's start bank depth. The pixels are the
// same (model/host_setup.h), the area and the cycles per pixel are not. Host setup has no
// coefficient banks to queue: tri_queue 1; back in the unit, the start's queue (2, config's
// default, when the start is a host-setup unit), and the default start depth, which a
// unit-setup unit does not use (so its points do not differ in a field no hardware has).
void span_setup_knobs(const UnitConfig& start, std::vector<Knob>& k) {
  const int unit_queue = start.host_setup() ? 2 : start.tri_queue;
  k.push_back(choice(
      "span setup", "span_setup", {"unit", "host"},
      [unit_queue](UnitConfig& c, int v) {
        c.span_setup = v ? SpanSetupSite::kHost : SpanSetupSite::kUnit;
        c.tri_queue = v ? 1 : unit_queue;
        if (!v) c.start_depth = UnitConfig::kStartDepth;
      },
      [](const UnitConfig& c) { return c.host_setup() ? 1 : 0; }));
  // Only a host-setup unit has a start bank: from a unit-setup start, each depth is a
  // host-setup point (depth 2 is the span_setup knob's host point, evaluated once).
  k.push_back(numeric(
      "span setup", "start_depth", 1, UnitConfig::kStartDepth,
      [](UnitConfig& c, int v) {
        c.span_setup = SpanSetupSite::kHost;
        c.tri_queue = 1;
        c.start_depth = v;
      },
      [](const UnitConfig& c) { return c.start_depth; }));
}

// The diffuse colour rolled into the series or multiplied in the unit: other pixels (kd L is
// quantized to spec_colour) and, with colour, a third of the diffuse series. With one channel
// the multiply saves no series and adds a multiplier per light, so a grey series start does
// not sweep it.
void diffuse_colour_knob(const UnitConfig& start, std::vector<Knob>& k) {
  if (start.channels == 1 && !start.diffuse_multiply()) return;
  k.push_back(choice(
      "diffuse colour", "diffuse_colour", {"series", "multiply"},
      [](UnitConfig& c, int v) {
        c.diffuse_colour = v ? DiffuseColour::kMultiply : DiffuseColour::kSeries;
      },
      [](const UnitConfig& c) { return c.diffuse_multiply() ? 1 : 0; }));
}

// The rungs of the start's pipelining ladder (derive/derive_config.h: combine_stages 0, 1, 2, then
// square_stages 2 on a pipelined W_m), labelled "c<combine_stages>" and " sq2". A start off the
// ladder (a config file's) is swept too, last.
void pipelining_knob(const UnitConfig& start, std::vector<Knob>& k) {
  std::vector<Pipelining> ladder = pipelining_ladder(start);
  const auto same = [](const Pipelining& a, const Pipelining& b) {
    return a.combine_stages == b.combine_stages && a.square_stages == b.square_stages;
  };
  const Pipelining own = pipelining_of(start);
  if (std::none_of(ladder.begin(), ladder.end(), [&](const Pipelining& p) { return same(p, own); }))
    ladder.push_back(own);
  std::vector<std::string> labels;
  labels.reserve(ladder.size());
  for (const Pipelining& p : ladder) {
    labels.push_back("c" + std::to_string(p.combine_stages) +
                     (p.square_stages != 1 ? " sq" + std::to_string(p.square_stages) : ""));
  }
  k.push_back(choice(
      "pipelining", "pipelining", std::move(labels),
      [ladder](UnitConfig& c, int v) {
        const Pipelining& p = ladder[static_cast<std::size_t>(v)];
        c.combine_stages = p.combine_stages;
        if (c.specular.kind == SpecularUnitKind::kWpow)
          c.specular.wpow.square_stages = p.square_stages;
      },
      [ladder, same](const UnitConfig& c) {
        const auto it = std::find_if(ladder.begin(), ladder.end(), [&](const Pipelining& p) {
          return same(p, pipelining_of(c));
        });
        return it == ladder.end() ? -1 : static_cast<int>(it - ladder.begin());
      }));
}

}  // namespace

std::vector<Knob> knobs_for(const UnitConfig& start, bool structure) {
  std::vector<Knob> k;
  width_knobs(start, k);
  // The structure changes cycles, area and clock (and, for the diffuse colour, pixels) rather
  // than narrowing a width: swept for the table and the Pareto front, not chosen by the error
  // search, which keeps the start's.
  if (structure) {
    const std::size_t first = k.size();
    span_setup_knobs(start, k);
    diffuse_colour_knob(start, k);
    pipelining_knob(start, k);
    for (std::size_t i = first; i < k.size(); ++i) k[i].searched = false;
  }
  // Output bits are what was asked for: swept for the table, never narrowed.
  k.push_back(numeric(
      "output", "out_bits", std::max(1, start.out_bits - 2), std::min(16, start.out_bits + 2),
      [](UnitConfig& c, int v) { c.out_bits = v; }, [](const UnitConfig& c) { return c.out_bits; },
      /*searched=*/false));
  return k;
}

}  // namespace shadesim
