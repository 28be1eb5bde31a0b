// Host-side setup of the specular units, and the error yardstick the setup fits against.
//
// Per material and unit, plan_specular() says how to pre-scale the light's specular t-quadratic
// into each series the unit reads (an affine map of t: scale every Taylor coefficient by `scale`,
// add `offset` to T0), which MATERIAL unit_params words to send, and which TABLE commands to
// load. Free per-exponent parameters (W_m's zeta, Schlick's n', the shared LUT's k) are fitted
// here, in double, by minimising the error metrics defined below.
//
// Series pre-scales (v = the unit's argument, x = what the series carries):
//   ideal    x = t
//   lut (a)  x = t * D/N                       table of v^n, reloaded per material
//   lut (b)  x = k (1 - t) / U * D/N * 2^-shift   one shared table of exp(-U v), U = 2^range_log2
//   schlick  num = t / n', den = (n' - (n' - 1) t) / n'
//   wpow     x = (zeta (t - 1) + 1) * 2^-shift, squarings s = log2(m_eff)
// `shift` keeps |x| <= 2^(iwl-2) of the series format for t in [-1.25, 1.25] (Taylor overshoot);
// the unit shifts it back (free wiring plus saturation).
//
// Error metrics (all against exact t^n in double, on named sample grids):
//   epicentre  max relative error where t^n >= 0.5 (Romanyuk's "before the cusp")
//   blooming   max relative error where 2^-8 <= t^n < 0.5 (q = 8 in Romanyuk's 2^-q bound: one
//              8-bit output step; his Table 1 does not state its bound)
//   absolute   max |f - t^n| over t in [0, 1], in 8-bit output LSBs (x 256)
#pragma once

#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "model/command_stream.h"
#include "model/unit_config.h"

namespace shadesim {

// ---------------------------------------------------------------- error metrics
struct SpecErrors {
  double epi_rel = 0;    // max relative error, epicentre
  double bloom_rel = 0;  // max relative error, blooming zone
  double abs_lsb = 0;    // max absolute error over [0, 1], 8-bit LSBs
};

// Sample points: `points` uniform over the epicentre [0.5^(1/n), 1], as many over the blooming
// zone [2^(-8/n), 0.5^(1/n)), and as many over [0, 1]; all three feed the absolute error.
SpecErrors measure_errors(double n, const std::function<double(double)>& f, int points = 1024);

// ---------------------------------------------------------------- float forms of the units
double wpow_float(double t, double zeta, int m);  // (zeta (t - 1) + 1)^m, base clamped to [0, 1]
double schlick_float(double t, double n);         // t / (n - n t + t), t clamped to [0, 1]
double exp_float(double t, double k);             // exp(-k (1 - t)), t clamped to [0, 1]

// The m a material uses on a unit with max_m: the largest power of two <= min(n, max_m)
// (1 for n < 2), so W_m's zero (n - m)/n is never negative.
int wpow_effective_m(double n, int max_m);

// Fitted parameters (kNone returns the paper's choice: n/m, n, n).
double fit_wpow_zeta(double n, int m, FitObjective objective);
double fit_schlick_n(double n, FitObjective objective);
double fit_exp_k(double n, FitObjective objective);

// ---------------------------------------------------------------- plan per material
struct SpecularSeriesPlan {
  // One (scale, offset) per series the unit reads for a light: series = scale * t + offset
  // (none: no series, no unit parameters).
  std::vector<std::pair<double, double>> affine;
  std::vector<int64_t> unit_params;  // MATERIAL unit_params
  std::vector<TableCmd> tables;      // per-exponent LUT: load after every switch to this material
  double parameter = 0;              // the zeta / n' / k used (0 for ideal and per-exponent LUT)
  int effective_m = 0;               // wpow only
  int64_t load_cycles = 0;           // cycles the TABLE reload costs on a switch (one entry/cycle)
};

// Throws std::invalid_argument when the exponent is not in (0, 1023] (the u10.16 word).
SpecularSeriesPlan plan_specular(const UnitConfig& config, double n);

// The function of t the configured unit approximates t^n with, in double (no widths): what it
// would give with exact arithmetic. ideal and per-exponent LUT: clamp01(t)^n (the table's
// sampling is a width, not a function); shared LUT: exp_float(t, k); Schlick: schlick_float(t, n');
// W_m: wpow_float(t, zeta, m_eff) - with the same fitted parameters plan_specular() uses; none: 0.
std::function<double(double)> unit_float_function(const UnitConfig& config, double n);

// The shared LUT's table (load once at stream start); empty unless lut + shared addressing.
std::vector<TableCmd> shared_lut_tables(const UnitConfig& config);

// Table contents: entry i = round(f(v_i) * 2^B), saturated to 2^B - 1, f = v^n (per exponent)
// or exp(-U v) (shared, n ignored). Split into TABLE commands of at most 65535 entries.
std::vector<int64_t> lut_entries(const LutConfig& c, double n);
// per_material: the table belongs to one material (a per-exponent LUT's reload after its
// MATERIAL; TableCmd::per_material).
std::vector<TableCmd> to_table_commands(const std::vector<int64_t>& entries,
                                        bool per_material = false);

// Smallest shift >= 0 that fits the affine map into the series format (see above).
int series_shift(const FixedFormat& series, double scale, double offset);

// ---------------------------------------------------------------- bit-accurate measurement
// Runs the configured SpecularUnit (config.specular) for exponent n over the metric grids, the
// series values formed exactly as plan_specular says and quantized into config.series.
SpecErrors measure_unit(const UnitConfig& config, double n, int points = 1024);

// ---------------------------------------------------------------- paper figures
// Bishop & Weimer's claim: largest n whose table of N one-byte entries stays within `tol`
// absolute error (full scale 1) with nearest-entry indexing of t (entries at cell centres).
// exact_entries: entries are exact t^n; otherwise rounded to 8 bits (value e / 256).
// Computed cell by cell at the cell edges (t^n is monotone, so the max is at an edge).
int bishop_n_max(int entries, double tol, bool exact_entries);
// The closed form for exact entries: floor(ln(1 - tol) / ln(1 - 1/(2N))).
int bishop_n_max_closed_form(int entries, double tol);

}  // namespace shadesim
