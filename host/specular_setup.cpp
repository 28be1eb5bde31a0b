#include "host/specular_setup.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "model/exponent_lut.h"
#include "model/specular_unit.h"
#include "model/wpow_unit.h"

namespace shadesim {

namespace {

constexpr double kBloomFloor = 1.0 / 256.0;  // 2^-q, q = 8
constexpr double kLsb8 = 256.0;

double rel(double f, double ref) { return std::fabs(f - ref) / ref; }

// Max of a (roughly unimodal) objective over [lo, hi]: coarse scan, then golden section around
// the best scan point. Returns the argument of the minimum.
double minimise(double lo, double hi, const std::function<double(double)>& g) {
  constexpr int kScan = 48;
  double best_p = lo, best_v = g(lo);
  for (int i = 1; i <= kScan; ++i) {
    const double p = lo + (hi - lo) * i / kScan;
    const double v = g(p);
    if (v < best_v) best_v = v, best_p = p;
  }
  const double step = (hi - lo) / kScan;
  double a = std::max(lo, best_p - step), b = std::min(hi, best_p + step);
  const double r = (std::sqrt(5.0) - 1.0) / 2.0;
  double c = b - r * (b - a), d = a + r * (b - a);
  double gc = g(c), gd = g(d);
  for (int it = 0; it < 40; ++it) {
    if (gc < gd) {
      b = d, d = c, gd = gc;
      c = b - r * (b - a), gc = g(c);
    } else {
      a = c, c = d, gc = gd;
      d = a + r * (b - a), gd = g(d);
    }
  }
  const double p = (a + b) / 2;
  return g(p) <= best_v ? p : best_p;
}

// The fit objectives, on a coarser grid than the reports (setup cost, not a report).
double objective(double n, FitObjective o, const std::function<double(double)>& f) {
  constexpr int kPoints = 256;
  if (o == FitObjective::kEpicentre) {
    const double te = std::pow(0.5, 1.0 / n);
    double worst = 0;
    for (int i = 0; i <= kPoints; ++i) {
      const double t = te + (1.0 - te) * i / kPoints;
      worst = std::max(worst, rel(f(t), std::pow(t, n)));
    }
    return worst;
  }
  // Absolute: dense where t^n is not negligible, coarse elsewhere.
  const double tq = std::pow(2.0, -16.0 / n);
  double worst = 0;
  for (int i = 0; i <= kPoints; ++i) {
    const double t1 = tq + (1.0 - tq) * i / kPoints;
    const double t2 = static_cast<double>(i) / kPoints;
    worst =
        std::max({worst, std::fabs(f(t1) - std::pow(t1, n)), std::fabs(f(t2) - std::pow(t2, n))});
  }
  return worst;
}

void check_exponent(double n) {
  if (!(n > 0.0) || n > 1023.0) {
    throw std::invalid_argument(
        "specular setup: exponent " + std::to_string(n) +
        " out of range; expected 0 < n <= 1023 (MATERIAL exponent is u10.16)");
  }
}

}  // namespace

SpecErrors measure_errors(double n, const std::function<double(double)>& f, int points) {
  SpecErrors e;
  const double te = std::pow(0.5, 1.0 / n);
  const double tb = std::pow(kBloomFloor, 1.0 / n);
  for (int i = 0; i <= points; ++i) {
    const double t_epi = te + (1.0 - te) * i / points;
    const double t_bloom = tb + (te - tb) * i / (points + 1);  // excludes te
    const double t_all = static_cast<double>(i) / points;
    const double f_epi = f(t_epi), f_bloom = f(t_bloom), f_all = f(t_all);
    const double r_epi = std::pow(t_epi, n), r_bloom = std::pow(t_bloom, n),
                 r_all = std::pow(t_all, n);
    e.epi_rel = std::max(e.epi_rel, rel(f_epi, r_epi));
    e.bloom_rel = std::max(e.bloom_rel, rel(f_bloom, r_bloom));
    e.abs_lsb = std::max({e.abs_lsb, std::fabs(f_epi - r_epi) * kLsb8,
                          std::fabs(f_bloom - r_bloom) * kLsb8, std::fabs(f_all - r_all) * kLsb8});
  }
  return e;
}

double wpow_float(double t, double zeta, int m) {
  const double b = std::clamp(zeta * (t - 1.0) + 1.0, 0.0, 1.0);
  return std::pow(b, m);
}

double schlick_float(double t, double n) {
  t = std::clamp(t, 0.0, 1.0);
  return t / (n - n * t + t);
}

double exp_float(double t, double k) { return std::exp(-k * (1.0 - std::clamp(t, 0.0, 1.0))); }

int wpow_effective_m(double n, int max_m) {
  int m = 1;
  while (2 * m <= max_m && 2 * m <= n) m *= 2;
  return m;
}

double fit_wpow_zeta(double n, int m, FitObjective o) {
  const double paper = n / m;
  if (o == FitObjective::kNone) return paper;
  return minimise(0.5 * paper, 1.5 * paper, [&](double z) {
    return objective(n, o, [&](double t) { return wpow_float(t, z, m); });
  });
}

double fit_schlick_n(double n, FitObjective o) {
  if (o == FitObjective::kNone) return n;
  return minimise(0.5 * n, 4.0 * n, [&](double p) {
    return objective(n, o, [&](double t) { return schlick_float(t, p); });
  });
}

double fit_exp_k(double n, FitObjective o) {
  if (o == FitObjective::kNone) return n;
  return minimise(0.5 * n, 2.0 * n, [&](double k) {
    return objective(n, o, [&](double t) { return exp_float(t, k); });
  });
}

int series_shift(const FixedFormat& series, double scale, double offset) {
  const double reach =
      std::max(std::fabs(1.25 * scale + offset), std::fabs(-1.25 * scale + offset));
  const double limit = std::ldexp(1.0, series.iwl - 2);
  int shift = 0;
  while (reach > std::ldexp(limit, shift) && shift < series.frac_bits()) ++shift;
  return shift;
}

std::vector<int64_t> lut_entries(const LutConfig& c, double n) {
  const FixedFormat entry{c.entry_bits, 0, false, Quantization::kRoundNearest, Overflow::kSaturate};
  const double range = std::ldexp(1.0, c.shared_range_log2);
  const int count = 1 << c.addr_bits;
  std::vector<int64_t> e(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    const double v = ExponentLut::sample_argument(c, i);
    const double f = c.addressing == LutAddressing::kShared ? std::exp(-range * v) : std::pow(v, n);
    e[static_cast<size_t>(i)] = entry.from_double(f);
  }
  return e;
}

std::vector<TableCmd> to_table_commands(const std::vector<int64_t>& entries, bool per_material) {
  constexpr size_t kMaxPerCommand = 65535;
  std::vector<TableCmd> cmds;
  for (size_t base = 0; base < entries.size(); base += kMaxPerCommand) {
    TableCmd t;
    t.base = static_cast<uint32_t>(base);
    t.per_material = per_material;
    const size_t end = std::min(entries.size(), base + kMaxPerCommand);
    t.entries.assign(entries.begin() + static_cast<long>(base),
                     entries.begin() + static_cast<long>(end));
    cmds.push_back(std::move(t));
  }
  return cmds;
}

SpecularSeriesPlan plan_specular(const UnitConfig& config, double n) {
  check_exponent(n);
  const SpecularConfig& s = config.specular;
  SpecularSeriesPlan p;
  switch (s.kind) {
    case SpecularUnitKind::kIdeal:
      p.affine = {{1.0, 0.0}};
      break;
    case SpecularUnitKind::kNone:
      break;  // no specular series and no unit parameters
    case SpecularUnitKind::kLut: {
      const double d = ExponentLut::argument_scale(s.lut);
      if (s.lut.addressing == LutAddressing::kPerExponent) {
        p.affine = {{d, 0.0}};
        p.unit_params = {0};
        p.tables = to_table_commands(lut_entries(s.lut, n), /*per_material=*/true);
        p.load_cycles = ExponentLut::reload_cycles(s.lut);
      } else {
        const double k = fit_exp_k(n, s.lut.fit);
        const double a = k / std::ldexp(1.0, s.lut.shared_range_log2) * d;  // x = a (1 - t)
        const int shift = series_shift(config.series, -a, a);
        p.affine = {{-std::ldexp(a, -shift), std::ldexp(a, -shift)}};
        p.unit_params = {shift};
        p.parameter = k;
      }
      break;
    }
    case SpecularUnitKind::kSchlick: {
      const double np = fit_schlick_n(n, s.schlick.fit);
      const double inv = 1.0 / std::max(1.0, np);
      p.affine = {{inv, 0.0}, {-(np - 1.0) * inv, np * inv}};
      p.parameter = np;
      break;
    }
    case SpecularUnitKind::kWpow: {
      const int m = wpow_effective_m(n, s.wpow.max_m);
      const double zeta = fit_wpow_zeta(n, m, s.wpow.fit);
      const int shift = series_shift(config.series, zeta, 1.0 - zeta);
      p.affine = {{std::ldexp(zeta, -shift), std::ldexp(1.0 - zeta, -shift)}};
      int squarings = 0;
      while ((1 << squarings) < m) ++squarings;
      p.unit_params = {shift, squarings};
      p.parameter = zeta;
      p.effective_m = m;
      break;
    }
  }
  return p;
}

std::function<double(double)> unit_float_function(const UnitConfig& config, double n) {
  const SpecularSeriesPlan plan = plan_specular(config, n);
  const SpecularConfig& s = config.specular;
  const double parameter = plan.parameter;
  switch (s.kind) {
    case SpecularUnitKind::kLut:
      if (s.lut.addressing == LutAddressing::kShared) {
        return [parameter](double t) { return exp_float(t, parameter); };
      }
      break;
    case SpecularUnitKind::kSchlick:
      return [parameter](double t) { return schlick_float(t, parameter); };
    case SpecularUnitKind::kWpow: {
      const int m = plan.effective_m;
      return [parameter, m](double t) { return wpow_float(t, parameter, m); };
    }
    case SpecularUnitKind::kNone:
      return [](double) { return 0.0; };
    case SpecularUnitKind::kIdeal:
      break;
  }
  return [n](double t) { return std::pow(std::clamp(t, 0.0, 1.0), n); };
}

std::vector<TableCmd> shared_lut_tables(const UnitConfig& config) {
  const SpecularConfig& s = config.specular;
  if (s.kind != SpecularUnitKind::kLut || s.lut.addressing != LutAddressing::kShared) return {};
  return to_table_commands(lut_entries(s.lut, 1.0));
}

SpecErrors measure_unit(const UnitConfig& config, double n, int points) {
  SpecularUnit unit(config);
  const SpecularSeriesPlan plan = plan_specular(config, n);
  MaterialCmd m;
  m.exponent = kExponentFormat.from_double(n);
  m.unit_params = plan.unit_params;
  unit.load_material(m);
  for (const TableCmd& t : shared_lut_tables(config)) unit.load_table(t);
  for (const TableCmd& t : plan.tables) unit.load_table(t);
  const FixedFormat& series = config.series;
  const FixedFormat& out = config.specular.out;
  int64_t values[2] = {0, 0};
  return measure_errors(
      n,
      [&](double t) {
        for (size_t i = 0; i < plan.affine.size(); ++i) {
          values[i] = series.from_double(plan.affine[i].first * t + plan.affine[i].second);
        }
        return out.to_double(unit.evaluate(values));
      },
      points);
}

int bishop_n_max(int entries, double tol, bool exact_entries) {
  LutConfig c;
  c.index = LutIndex::kTruncate;  // cell-centre entries: truncation = nearest entry
  c.interp_bits = 0;
  int bits = 0;
  while ((1 << bits) < entries) ++bits;
  if ((1 << bits) != entries)
    throw std::invalid_argument("bishop_n_max: entries must be a power of two");
  c.addr_bits = bits;
  c.entry_bits = 8;
  const FixedFormat byte{8, 0, false, Quantization::kRoundNearest, Overflow::kSaturate};
  auto worst = [&](int n) {
    double w = 0;
    for (int i = 0; i < entries; ++i) {
      const double s = std::pow(ExponentLut::sample_argument(c, i), n);
      const double value = exact_entries ? s : byte.to_double(byte.from_double(s));
      const double lo = std::pow(static_cast<double>(i) / entries, n);
      const double hi = std::pow(static_cast<double>(i + 1) / entries, n);
      w = std::max({w, std::fabs(value - lo), std::fabs(hi - value)});
    }
    return w;
  };
  int n = 0;
  while (n < 100000 && worst(n + 1) <= tol) ++n;
  return n;
}

int bishop_n_max_closed_form(int entries, double tol) {
  return static_cast<int>(std::floor(std::log(1.0 - tol) / std::log(1.0 - 1.0 / (2.0 * entries))));
}

}  // namespace shadesim
