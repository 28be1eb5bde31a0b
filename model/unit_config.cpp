#include "model/unit_config.h"

#include <sstream>
#include <stdexcept>

namespace shadesim {

void UnitConfig::validate() const {
  auto fail = [](const std::string& msg) { throw std::invalid_argument("unit config: " + msg); };
  if (channels != 1 && channels != 3)
    fail("channels must be 1 or 3, got " + std::to_string(channels));
  if (lights < 1 || lights > 8) fail("lights must be 1..8, got " + std::to_string(lights));
  if (xy_bits < 4 || xy_bits > 15) fail("xy_bits must be 4..15, got " + std::to_string(xy_bits));
  if (offset_bits < 2 || offset_bits > kMaxOffsetBits)
    fail("offset_bits must be 2.." + std::to_string(kMaxOffsetBits) + ", got " +
         std::to_string(offset_bits));
  if (out_bits < 1 || out_bits > 16)
    fail("out_bits must be 1..16, got " + std::to_string(out_bits));
  if (port_words != 1 && port_words != 2 && port_words != 4 && port_words != 8)
    fail("port_words must be 1, 2, 4 or 8, got " + std::to_string(port_words));
  if (tri_queue < 1 || tri_queue > 8)
    fail("tri_queue must be 1..8, got " + std::to_string(tri_queue));
  if (lanes != 1 && lanes != 2 && lanes != 4)
    fail("lanes must be 1, 2 or 4, got " + std::to_string(lanes));
  if (material_buffers != 1 && material_buffers != 2)
    fail("material_buffers must be 1 or 2, got " + std::to_string(material_buffers));
  if (span_setup != SpanSetupSite::kUnit && span_setup != SpanSetupSite::kHost)
    fail("span_setup must be unit or host");
  if (host_setup() && tri_queue != 1)
    fail("tri_queue must be 1 with span_setup host, got " + std::to_string(tri_queue) +
         ": the unit holds no triangle coefficients to queue (the host sends every span's start "
         "values)");
  if (start_depth != 1 && start_depth != 2)
    fail("start_depth must be 1 or 2, got " + std::to_string(start_depth));
  if (combine_stages < 0 || combine_stages > 2)
    fail("combine_stages must be 0, 1 or 2, got " + std::to_string(combine_stages));
  if (diffuse_colour != DiffuseColour::kSeries && diffuse_colour != DiffuseColour::kMultiply)
    fail("diffuse_colour must be series or multiply");
  coef.validate("unit config: coef");
  series.validate("unit config: series");
  spec_colour.validate("unit config: spec_colour");
  specular.out.validate("unit config: specular.out");
  specular.validate();
  if (!coef.is_signed || !series.is_signed) fail("coef and series formats must be signed");
  if (spec_colour.is_signed || specular.out.is_signed)
    fail("spec_colour and specular.out formats must be unsigned");
  if (coef.overflow == Overflow::kWrap && coef.iwl < series.iwl)
    fail("a wrapping coef format needs at least the series' integer bits (" + coef.to_string() +
         " vs " + series.to_string() + "), or the modulo arithmetic loses the value");
  if (!coef_term_iwl.empty()) {
    if (coef_term_iwl.size() != 6)
      fail("coef_term_iwl needs 6 entries (T0..T5), got " + std::to_string(coef_term_iwl.size()));
    for (size_t t = 0; t < coef_term_iwl.size(); ++t) {
      const int iwl = coef_term_iwl[t];
      const std::string name = "coef_term_iwl[" + std::to_string(t) + "] = " + std::to_string(iwl);
      if (iwl > coef.iwl) fail(name + ": more integer bits than coef " + coef.to_string());
      if (iwl + coef.frac_bits() < 2)
        fail(name + ": leaves fewer than 2 bits with coef's " + std::to_string(coef.frac_bits()) +
             " fraction bits");
    }
  }
  if (series.iwl < 2) fail("series needs at least 2 integer bits (sign + 1) to hold 1.0");
  if (series.frac_bits() < out_bits) fail("series needs at least out_bits fraction bits");
  // Span setup multiplies coefficients by offsets up to 2^(xy_bits+1) squared; the exact
  // intermediate must fit the model's 128-bit arithmetic and the RTL's declared widths.
  if (coef.wl + 2 * (xy_bits + 2) + 4 > 120) fail("coef too wide for span setup's intermediate");
  if (specular.out.iwl < 1) fail("specular.out needs an integer bit to hold 1.0");
  if (spec_colour.iwl < 1) fail("spec_colour needs an integer bit to hold 1.0");
}

FixedFormat UnitConfig::coef_term(int t) const {
  if (coef_term_iwl.empty()) return coef;
  const int iwl = coef_term_iwl.at(static_cast<size_t>(t));
  if (iwl == coef.iwl) return coef;
  return {coef.frac_bits() + iwl, iwl, true, coef.quant, Overflow::kSaturate};
}

std::string to_string(SpanSetupSite s) { return s == SpanSetupSite::kHost ? "host" : "unit"; }

SpanSetupSite parse_span_setup(const std::string& text, const std::string& what) {
  if (text == "unit") return SpanSetupSite::kUnit;
  if (text == "host") return SpanSetupSite::kHost;
  throw std::invalid_argument(what + ": unknown span setup '" + text + "'; expected unit or host");
}

std::string to_string(DiffuseColour d) {
  return d == DiffuseColour::kMultiply ? "multiply" : "series";
}

DiffuseColour parse_diffuse_colour(const std::string& text, const std::string& what) {
  if (text == "series") return DiffuseColour::kSeries;
  if (text == "multiply") return DiffuseColour::kMultiply;
  throw std::invalid_argument(what + ": unknown diffuse colour '" + text +
                              "'; expected series or multiply");
}

std::string UnitConfig::to_string() const {
  std::ostringstream os;
  os << (channels == 1 ? "grey" : "rgb") << '/' << lights << "L coef=" << coef.to_string();
  if (!coef_term_iwl.empty()) {
    os << " terms=";
    for (size_t t = 0; t < coef_term_iwl.size(); ++t) os << (t ? "," : "") << coef_term_iwl[t];
  }
  os << " series=" << series.to_string() << " out=" << out_bits
     << " spec=" << shadesim::to_string(specular.kind) << ':' << specular.out.to_string();
  if (offset_bits != kMaxOffsetBits) os << " ofs=" << offset_bits;
  if (port_words != 1) os << " port=" << port_words << 'w';
  if (tri_queue != 1) os << " triq=" << tri_queue;
  if (lanes != 1) os << " lanes=" << lanes;
  if (material_buffers != 1) os << " matbuf=" << material_buffers;
  if (host_setup()) os << " setup=host";
  if (host_setup() && start_depth != kStartDepth) os << " start_depth=" << start_depth;
  if (diffuse_multiply()) os << " diffuse=multiply";
  if (combine_stages != 0) os << " combine_stages=" << combine_stages;
  return os.str();
}

}  // namespace shadesim
