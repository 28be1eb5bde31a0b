#include "derive/colour_rules.h"

#include <algorithm>
#include <cmath>

#include "derive/helpers.h"

namespace shadesim {
namespace {

// Neither is narrowed below the default's fraction bits: the shares bound the worst case, and
// narrower colours or outputs were measured to cost suzanne's own unit its 1 LSB (2 LSB).
int min_colour_frac() { return UnitConfig{}.spec_colour.frac_bits(); }
int min_specular_out_frac() { return SpecularConfig{}.out.frac_bits(); }

// Fewest integer bits (>= 1: UnitConfig holds 1.0) of an unsigned format with `frac` fraction
// bits whose largest value, 2^iwl - 2^-frac, is at least `max`, so rounding never saturates.
int unsigned_integer_bits(double max, int frac) {
  int iwl = 1;
  while (iwl < 40 && std::ldexp(1.0, iwl) - std::ldexp(1.0, -frac) < max) ++iwl;
  return iwl;
}

// The smallest fraction bits F with 2^-F x weight <= allowed (weight 0: none needed).
int fraction_bits_for(double weight, double allowed) {
  int frac = 0;
  while (frac < 40 && std::ldexp(weight, -frac) > allowed) ++frac;
  return frac;
}

}  // namespace

double colour_product_max(double colour_max, double series_max) {
  return colour_max * std::max(1.0, series_max);
}

const DerivationRule kSpecColourRule = {
    "spec_colour",
    "integer bits: every ks_c L_c (and kd_c L_c multiplied) unsaturated; fraction bits F: "
    "rounding 2^-(F+1) per word (and, multiplied, N.L truncated to F bits times kd_c L_c) summed "
    "over the lights <= 3/16 of the budget; at least the default's fraction bits"};

// spec_colour carries ks_c L_c (and with the multiply kd_c L_c) per light and channel. Integer
// bits: the largest colour, unsaturated. Fraction bits F: in one channel each light's words
// reach the output as rounding 2^-(F+1) times the specular intensity (<= 1) and, multiplied,
// 2^-(F+1) times N.L (<= 1) plus N.L truncated to F bits (2^-F) times kd_c L_c; summed over the
// lights within 3/16 of the budget; at least the default's fraction bits.
std::string derive_spec_colour(const std::vector<SceneInfo>& scenes, const ConfigMeasurements& ms,
                               UnitConfig& cfg) {
  const bool specular = cfg.specular.kind != SpecularUnitKind::kNone;
  if (!specular && !cfg.diffuse_multiply()) {
    return "not read: no specular term and the diffuse colour is rolled into the series "
           "(default kept)";
  }
  const LightColours colours = light_colours(scenes, cfg);
  double weight = 0;
  for (int l = 0; l < cfg.lights; ++l) {
    const size_t i = static_cast<size_t>(l);
    if (colours.specular[i] > 0) weight += 0.5;
    if (cfg.diffuse_multiply() && colours.diffuse[i] > 0) weight += 0.5 + colours.diffuse[i];
  }
  const double allowed = ms.colour_share_lsb * std::ldexp(1.0, -cfg.out_bits);
  const int rule = fraction_bits_for(weight, allowed);
  const int frac = std::max(min_colour_frac(), rule);
  const double top = colours.max();
  const int iwl = unsigned_integer_bits(top, frac);
  cfg.spec_colour.iwl = iwl;
  cfg.spec_colour.wl = iwl + frac;
  return "integer " + std::to_string(iwl) + ": colours (ks_c L_c" +
         (cfg.diffuse_multiply() ? std::string(", kd_c L_c") : std::string()) + ") reach " +
         fmt(top) + " < 2^" + std::to_string(iwl) + " (unsaturated); fraction " +
         std::to_string(frac) + ": rounding 2^-(F+1) per word" +
         (cfg.diffuse_multiply() ? " and N.L truncated to F bits times kd_c L_c" : "") +
         ", summed over the lights (" + fmt(weight) + " x 2^-F), <= " + fmt(ms.colour_share_lsb) +
         " LSB (3/16 of the budget)" +
         (frac > rule ? " (at least the default's " + std::to_string(min_colour_frac()) + ")" : "");
}

const DerivationRule kSpecularOutRule = {
    "specular out",
    "fraction bits F: the output truncated to F bits times the specular colours ks_c L_c summed "
    "over the lights, 2^-F x sum, <= budget/16; at least the default's fraction bits"};

// The specular unit's output s (in [0, 1]) is truncated to F fraction bits, and each light's
// s x ks_c L_c adds to a channel: 2^-F x the sum over lights of the largest ks_c L_c, within
// budget/16; at least the default's fraction bits.
std::string derive_specular_out(const std::vector<SceneInfo>& scenes, const ConfigMeasurements& ms,
                                UnitConfig& cfg) {
  if (cfg.specular.kind == SpecularUnitKind::kNone) return "";
  const LightColours colours = light_colours(scenes, cfg);
  double weight = 0;
  for (double k : colours.specular) weight += k;
  const double allowed = ms.specular_out_share_lsb * std::ldexp(1.0, -cfg.out_bits);
  const int rule = fraction_bits_for(weight, allowed);
  const int frac = std::max(min_specular_out_frac(), rule);
  cfg.specular.out.iwl = 1;
  cfg.specular.out.wl = 1 + frac;
  return "; out u1." + std::to_string(frac) +
         ": the output truncated to F bits times the "
         "specular colours summed over the lights (" +
         fmt(weight) + " x 2^-F) <= " + fmt(ms.specular_out_share_lsb) + " LSB (budget/16)" +
         (frac > rule ? " (at least the default's " + std::to_string(min_specular_out_frac()) + ")"
                      : "");
}

}  // namespace shadesim
