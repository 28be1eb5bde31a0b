#include "model/command_stream.h"

#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <iostream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <utility>

#include "model/coef_packing.h"
#include "model/json_error.h"
#include "model/specular_units.h"
#include "model/start_packing.h"
#include "model/text_file.h"
#include "model/unit_config_file.h"

namespace shadesim {
namespace {

constexpr uint64_t kMask16 = CommandWord::kFieldMask;

// A command's place in its source, formatted only when an error names it: validating a frame's
// stream must not build a string per command.
struct Where {
  const std::string& source;
  size_t index;
  const char* unit;  // "command", "word"; nullptr: index is a text line's number
  std::string text() const {
    return source + ":" + (unit ? std::string(unit) + " " : std::string()) + std::to_string(index) +
           ": ";
  }
};
std::string operator+(const Where& w, const char* s) { return w.text() + s; }
std::ostream& operator<<(std::ostream& os, const Where& w) { return os << w.text(); }

Where where(const std::string& source, size_t index, const char* unit) {
  return {source, index, unit};
}

bool fits(int64_t raw, const FixedFormat& f) { return raw >= f.raw_min() && raw <= f.raw_max(); }

// One rule for every payload check, so binary and text input fail with the same message.
void check_payload(const Where& loc, const char* field, const std::vector<int64_t>& values,
                   size_t expected_count, const FixedFormat& format) {
  if (values.size() != expected_count) {
    throw CommandStreamError(loc + field + ": expected " + std::to_string(expected_count) +
                             " values, got " + std::to_string(values.size()));
  }
  for (size_t i = 0; i < values.size(); ++i) {
    if (!fits(values[i], format)) {
      throw CommandStreamError(loc + field + "[" + std::to_string(i) +
                               "] = " + std::to_string(values[i]) + " does not fit format " +
                               format.to_string());
    }
  }
}

void validate_command(const Command& cmd, const UnitConfig& cfg, const Where& loc) {
  const int64_t xy_max = (int64_t{1} << cfg.xy_bits) - 1;
  if (const auto* m = std::get_if<MaterialCmd>(&cmd)) {
    check_payload(loc, "material.ambient", m->ambient, cfg.channels, cfg.series);
    check_payload(loc, "material.spec_colour", m->spec_colour, static_cast<size_t>(cfg.colours()),
                  cfg.spec_colour);
    // Diffuse colour multiply: kd_c L_c per light and channel; rolled into the series: none.
    check_payload(loc, "material.diffuse_colour", m->diffuse_colour,
                  cfg.diffuse_multiply() ? static_cast<size_t>(cfg.colours()) : 0, cfg.spec_colour);
    const int64_t exp_max = (int64_t{1000}) << kExponentFracBits;
    if (m->exponent < 0 || m->exponent > exp_max) {
      throw CommandStreamError(loc + "material.exponent = " + std::to_string(m->exponent) +
                               ": expected 0..1000 in u10.16 (raw 0.." + std::to_string(exp_max) +
                               ")");
    }
    if (m->payload_words() > kMask16) {
      throw CommandStreamError(loc + "material: too many payload words");
    }
    if (cfg.diffuse_multiply() && m->gate_only != 0) {
      throw CommandStreamError(loc + "material.gate_only = " + std::to_string(m->gate_only) +
                               ": expected 0 with diffuse_colour multiply (each light's one "
                               "series is N.L itself and gates its specular term)");
    }
    if (m->gate_only >> cfg.lights != 0) {
      throw CommandStreamError(loc + "material.gate_only = " + std::to_string(m->gate_only) +
                               ": expected a mask of the unit's " + std::to_string(cfg.lights) +
                               " lights (0.." + std::to_string((1u << cfg.lights) - 1) + ")");
    }
  } else if (const auto* t = std::get_if<TriangleCmd>(&cmd)) {
    if (cfg.host_setup()) {
      throw CommandStreamError(loc +
                               "tri: a unit with span_setup host takes no TRIANGLE (each "
                               "SPAN carries its start values)");
    }
    const size_t expected = static_cast<size_t>(cfg.series_per_triangle()) * kTermsPerSeries;
    check_payload(loc, "tri.coef", t->coef, expected, cfg.coef);
    if (!cfg.coef_term_iwl.empty()) {
      for (size_t i = 0; i < t->coef.size(); ++i) {
        const FixedFormat term = cfg.coef_term(static_cast<int>(i % kTermsPerSeries));
        if (!fits(t->coef[i], term)) {
          throw CommandStreamError(loc + "tri.coef[" + std::to_string(i) +
                                   "] = " + std::to_string(t->coef[i]) + " does not fit term T" +
                                   std::to_string(i % kTermsPerSeries) + "'s format " +
                                   term.to_string() + " (coef_term_iwl)");
        }
      }
    }
    if (t->xo < -32768 || t->xo > 32767 || t->yo < -32768 || t->yo > 32767) {
      throw CommandStreamError(loc + "tri: origin outside the signed 16-bit range");
    }
  } else if (const auto* s = std::get_if<SpanCmd>(&cmd)) {
    if (s->y < 0 || s->y > xy_max || s->x0 < 0 || s->x0 > xy_max) {
      throw CommandStreamError(loc + "span: y and x0 must be 0.." + std::to_string(xy_max) +
                               " (xy_bits " + std::to_string(cfg.xy_bits) +
                               "), got y=" + std::to_string(s->y) + " x0=" + std::to_string(s->x0));
    }
    if (s->length < 1 || int64_t{s->x0} + s->length - 1 > xy_max) {
      throw CommandStreamError(loc + "span: length must be >= 1 and end inside the screen, got " +
                               std::to_string(s->length) + " from x0=" + std::to_string(s->x0));
    }
    // Host span setup: v, d, d2 per series (start_packing.h); unit setup: none.
    const size_t starts = cfg.host_setup() ? static_cast<size_t>(StartLayout::of(cfg).values) : 0;
    check_payload(loc, "span.starts", s->starts, starts, cfg.series);
  } else if (const auto* tb = std::get_if<TableCmd>(&cmd)) {
    // An empty TABLE is legal: a header with no payload (it still waits like any TABLE).
    if (tb->entries.size() > kMask16 || tb->base > kMask16) {
      throw CommandStreamError(loc + "table: expected 0..65535 entries at base 0..65535");
    }
  }
}

// Span setup takes the span's first-pixel offsets from its triangle's origin in offset_bits
// signed bits (rtl/span_setup.sv wraps them): a stream whose offsets do not fit would shade
// wrong pixels, so it is rejected naming both commands.
void check_span_offsets(const SpanCmd& s, const TriangleCmd& t, size_t tri_at,
                        const UnitConfig& cfg, const Where& loc) {
  const int64_t dx = int64_t{s.x0} - t.xo, dy = int64_t{s.y} - t.yo;
  if (cfg.offsets_fit(dx, dy)) return;
  const int64_t hi = (int64_t{1} << (cfg.offset_bits - 1)) - 1;
  throw CommandStreamError(
      loc + "span y=" + std::to_string(s.y) + " x0=" + std::to_string(s.x0) +
      ": offsets dx=" + std::to_string(dx) + " dy=" + std::to_string(dy) + " from the origin (" +
      std::to_string(t.xo) + ", " + std::to_string(t.yo) + ") of the triangle at command " +
      std::to_string(tri_at) + " do not fit offset_bits=" + std::to_string(cfg.offset_bits) + " (" +
      std::to_string(-hi - 1) + ".." + std::to_string(hi) +
      "): re-origin the triangle or widen it");
}

// The header line's UnitConfig JSON (defined with the JSON reader below).
UnitConfig header_config(const std::string& text, const std::string& source,
                         const std::function<std::string(const JsonTextError&)>& syntax_at);
}  // namespace

void CommandStream::validate(const std::string& source) const {
  config.validate();
  const TriangleCmd* tri = nullptr;
  size_t tri_at = 0;
  for (size_t i = 0; i < commands.size(); ++i) {
    validate_command(commands[i], config, where(source, i, "command"));
    if (const auto* t = std::get_if<TriangleCmd>(&commands[i])) {
      tri = t;
      tri_at = i;
    } else if (const auto* s = std::get_if<SpanCmd>(&commands[i]); s && tri) {
      check_span_offsets(*s, *tri, tri_at, config, where(source, i, "command"));
    }
  }
}

std::vector<uint64_t> CommandStream::encode() const {
  std::vector<uint64_t> words;
  words.reserve(word_count());  // a 4K frame's words: no doubling growth on top of the stream
  const CoefLayout layout = CoefLayout::of(config);
  const StartLayout start_layout = StartLayout::of(config);
  for (const auto& cmd : commands) {
    if (const auto* m = std::get_if<MaterialCmd>(&cmd)) {
      words.push_back(CommandWord::material(m->payload_words(), m->gate_only).bits);
      for (auto v : m->ambient) words.push_back(static_cast<uint64_t>(v));
      for (auto v : m->spec_colour) words.push_back(static_cast<uint64_t>(v));
      for (auto v : m->diffuse_colour) words.push_back(static_cast<uint64_t>(v));
      words.push_back(static_cast<uint64_t>(m->exponent));
      for (auto v : m->unit_params) words.push_back(static_cast<uint64_t>(v));
    } else if (const auto* t = std::get_if<TriangleCmd>(&cmd)) {
      words.push_back(
          CommandWord::triangle(t->xo, t->yo, static_cast<uint64_t>(layout.words)).bits);
      for (auto w : layout.pack(t->coef)) words.push_back(w);
    } else if (const auto* s = std::get_if<SpanCmd>(&cmd)) {
      words.push_back(CommandWord::span(s->y, s->x0, s->length, s->last_in_row).bits);
      if (config.host_setup()) {
        for (auto w : start_layout.pack(s->starts)) words.push_back(w);
      }
    } else if (const auto* tb = std::get_if<TableCmd>(&cmd)) {
      words.push_back(CommandWord::table(tb->base, tb->entries.size(), tb->per_material).bits);
      for (auto v : tb->entries) words.push_back(static_cast<uint64_t>(v));
    } else {
      words.push_back(CommandWord::end_frame().bits);
    }
  }
  return words;
}

size_t CommandStream::word_count() const {
  const auto triangle_words = static_cast<size_t>(CoefLayout::of(config).words);
  const auto span_payload =
      config.host_setup() ? static_cast<size_t>(StartLayout::of(config).words) : size_t{0};
  size_t words = 0;
  for (const auto& cmd : commands) {
    if (const auto* m = std::get_if<MaterialCmd>(&cmd)) {
      words += 1 + m->payload_words();
    } else if (std::holds_alternative<TriangleCmd>(cmd)) {
      words += 1 + triangle_words;
    } else if (std::holds_alternative<SpanCmd>(cmd)) {
      words += 1 + span_payload;
    } else if (const auto* tb = std::get_if<TableCmd>(&cmd)) {
      words += 1 + tb->entries.size();
    } else {
      words += 1;
    }
  }
  return words;
}

CommandStream CommandStream::decode(const std::vector<uint64_t>& words, const UnitConfig& config,
                                    const std::string& source) {
  CommandStream cs;
  cs.config = config;
  const CoefLayout layout = CoefLayout::of(config);
  size_t i = 0;
  auto take = [&](size_t count, size_t at) {
    if (i + count > words.size()) {
      throw CommandStreamError(where(source, at, "word") + "command needs " +
                               std::to_string(count) + " payload words, stream ends after " +
                               std::to_string(words.size() - i));
    }
    std::vector<int64_t> out(words.begin() + static_cast<long>(i),
                             words.begin() + static_cast<long>(i + count));
    i += count;
    return out;
  };
  while (i < words.size()) {
    const size_t at = i;
    const CommandWord h{words[i++]};
    const auto op = static_cast<uint8_t>(h.opcode());
    const size_t count = h.count();
    switch (static_cast<Opcode>(op)) {
      case Opcode::kMaterial: {
        const auto colours = static_cast<long>(config.colours());
        const long diffuse = config.diffuse_multiply() ? colours : 0;
        const size_t fixed = static_cast<size_t>(config.channels + colours + diffuse + 1);
        if (count < fixed) {
          throw CommandStreamError(where(source, at, "word") + "material: expected at least " +
                                   std::to_string(fixed) + " payload words, header says " +
                                   std::to_string(count));
        }
        auto p = take(count, at);
        MaterialCmd m;
        m.ambient.assign(p.begin(), p.begin() + config.channels);
        const auto spec_at = p.begin() + config.channels;
        m.spec_colour.assign(spec_at, spec_at + colours);
        m.diffuse_colour.assign(spec_at + colours, spec_at + colours + diffuse);
        m.exponent = p[fixed - 1];
        m.unit_params.assign(p.begin() + static_cast<long>(fixed), p.end());
        m.gate_only = h.material_gate_only();
        cs.commands.emplace_back(std::move(m));
        break;
      }
      case Opcode::kTriangle: {
        TriangleCmd t;
        t.xo = h.tri_xo();
        t.yo = h.tri_yo();
        if (count != static_cast<size_t>(layout.words)) {
          throw CommandStreamError(where(source, at, "word") + "tri: expected " +
                                   std::to_string(layout.words) +
                                   " payload words (the unit's coefficient layout), header says " +
                                   std::to_string(count));
        }
        const auto payload = take(count, at);
        std::vector<uint64_t> packed(payload.begin(), payload.end());
        t.coef = layout.unpack(packed.data());
        cs.commands.emplace_back(std::move(t));
        break;
      }
      case Opcode::kSpan: {
        SpanCmd s;
        s.last_in_row = h.span_last();
        s.y = h.span_y();
        s.x0 = h.span_x0();
        s.length = h.span_length();
        if (config.host_setup()) {
          const StartLayout start_layout = StartLayout::of(config);
          const auto payload = take(static_cast<size_t>(start_layout.words), at);
          const std::vector<uint64_t> packed(payload.begin(), payload.end());
          s.starts = start_layout.unpack(packed.data());
        }
        cs.commands.emplace_back(std::move(s));
        break;
      }
      case Opcode::kTable: {
        TableCmd tb;
        tb.base = h.table_base();
        tb.per_material = h.table_per_material();
        tb.entries = take(count, at);
        cs.commands.emplace_back(std::move(tb));
        break;
      }
      case Opcode::kEndFrame:
        cs.commands.emplace_back(EndFrameCmd{});
        break;
      default: {
        std::ostringstream os;
        os << where(source, at, "word") << "unknown opcode 0x" << std::hex << int{op}
           << "; expected 0x01 material, 0x02 tri, 0x03 span, 0x04 table, 0x0f end";
        throw CommandStreamError(os.str());
      }
    }
    validate_command(cs.commands.back(), config, where(source, at, "word"));
  }
  return cs;
}

void CommandStream::write_text(std::ostream& os) const {
  os << "shadesim-commands " << kCommandStreamVersion << ' ' << config_to_json(config) << '\n';
  auto list = [&os](const std::vector<int64_t>& v) {
    for (auto x : v) os << ' ' << x;
  };
  for (const auto& cmd : commands) {
    if (const auto* m = std::get_if<MaterialCmd>(&cmd)) {
      os << "material ambient";
      list(m->ambient);
      os << " spec_colour";
      list(m->spec_colour);
      if (!m->diffuse_colour.empty()) {
        os << " diffuse_colour";
        list(m->diffuse_colour);
      }
      os << " exponent " << m->exponent << " params";
      list(m->unit_params);
      if (m->gate_only != 0) os << " gate_only " << m->gate_only;
      os << '\n';
    } else if (const auto* t = std::get_if<TriangleCmd>(&cmd)) {
      os << "tri " << t->xo << ' ' << t->yo;
      for (size_t k = 0; k < t->coef.size(); ++k) {
        if (k % kTermsPerSeries == 0) os << " |";
        os << ' ' << t->coef[k];
      }
      os << '\n';
    } else if (const auto* s = std::get_if<SpanCmd>(&cmd)) {
      os << "span " << s->y << ' ' << s->x0 << ' ' << s->length << (s->last_in_row ? " last" : "");
      for (size_t k = 0; k < s->starts.size(); ++k) {
        if (k % StartLayout::kValuesPerSeries == 0) os << " |";
        os << ' ' << s->starts[k];
      }
      os << '\n';
    } else if (const auto* tb = std::get_if<TableCmd>(&cmd)) {
      os << "table " << tb->base;
      list(tb->entries);
      os << (tb->per_material ? " material" : "") << '\n';
    } else {
      os << "end\n";
    }
  }
}

namespace {

constexpr int64_t kField16 = 0xFFFF;

// One line of the text form after its first word `op`, and where it is (file:line: ) for the
// errors.
struct TextLine {
  std::istringstream& ls;
  const std::string& loc;
  const std::string& op;

  // Reads one integer of a bounded field; a value outside [lo, hi] is an error, never truncated.
  int64_t read_int(const char* field, int64_t lo = INT64_MIN, int64_t hi = INT64_MAX) {
    long long v = 0;
    if (!(ls >> v)) throw CommandStreamError(loc + op + ": expected an integer for " + field);
    if (v < lo || v > hi) {
      throw CommandStreamError(loc + op + ": " + field + " = " + std::to_string(v) +
                               " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
    }
    return static_cast<int64_t>(v);
  }
  // Reads integers until the next keyword (or end of line); leaves the keyword in `next`.
  std::vector<int64_t> read_list(std::string* next) {
    std::vector<int64_t> v;
    std::string tok;
    next->clear();
    while (ls >> tok) {
      try {
        size_t used = 0;
        const long long x = std::stoll(tok, &used);
        if (used != tok.size()) throw std::invalid_argument(tok);
        v.push_back(x);
      } catch (const std::logic_error&) {
        *next = tok;
        break;
      }
    }
    return v;
  }
  void expect_keyword(const std::string& got, const char* want) const {
    if (got != want) {
      throw CommandStreamError(loc + op + ": expected keyword '" + want + "', got '" + got + "'");
    }
  }
};

// Version 1 headers wrote a saturating format without a suffix ("s4.28"), which version 2 reads
// as sc_fix does (truncate, wrap): a version-1 header's suffix-less formats get their ":sat".
std::string version1_formats(const std::string& json) {
  static const std::regex suffixless(R"re("([su]\d+\.\d+(:(trn|rnd))?)")re");
  return std::regex_replace(json, suffixless, "\"$1:sat\"");
}

// The header line, 'shadesim-commands 2 {config}' (`line`, line number `line_no`): the unit.
UnitConfig read_header(TextLine& in, const std::string& line, const std::string& source,
                       size_t line_no) {
  if (in.op != "shadesim-commands") {
    throw CommandStreamError(in.loc + "expected the header 'shadesim-commands 2 {config}', got '" +
                             in.op + "'");
  }
  int version = 0;
  if (!(in.ls >> version) || version < 1 || version > kCommandStreamVersion) {
    throw CommandStreamError(in.loc + "unsupported command-stream version; expected 1 or " +
                             std::to_string(kCommandStreamVersion));
  }
  // The JSON's first column in the line, so a syntax error names its column in the file.
  std::streamoff json_at = in.ls.tellg();
  if (json_at < 0) json_at = static_cast<std::streamoff>(line.size());  // nothing after
  std::string json;
  std::getline(in.ls, json);
  if (json.find_first_not_of(" \t\r") == std::string::npos) {
    throw CommandStreamError(source + ":" + std::to_string(line_no) + ":" +
                             std::to_string(json_at + 1) +
                             ": expected the unit's config JSON object after "
                             "'shadesim-commands " +
                             std::to_string(version) + "', got the end of the line");
  }
  if (version == 1) json = version1_formats(json);
  return header_config(json, in.loc, [&](const JsonTextError& error) {
    // The header is one line: the error's column in the JSON, moved to the file's column.
    const size_t colon = error.place.rfind(':');
    if (colon == std::string::npos || colon == 0) return in.loc;
    return source + ":" + std::to_string(line_no) + ":" +
           std::to_string(static_cast<size_t>(json_at) +
                          std::stoul(error.place.substr(colon + 1))) +
           ": ";
  });
}

MaterialCmd read_material(TextLine& in) {
  MaterialCmd m;
  std::string kw;
  in.ls >> kw;
  in.expect_keyword(kw, "ambient");
  m.ambient = in.read_list(&kw);
  in.expect_keyword(kw, "spec_colour");
  m.spec_colour = in.read_list(&kw);
  if (kw == "diffuse_colour") m.diffuse_colour = in.read_list(&kw);
  in.expect_keyword(kw, "exponent");
  m.exponent = in.read_int("exponent");
  in.ls >> kw;
  in.expect_keyword(kw, "params");
  m.unit_params = in.read_list(&kw);
  if (kw == "gate_only") {
    m.gate_only = static_cast<uint32_t>(in.read_int("gate_only", 0, kField16));
    kw.clear();
    in.ls >> kw;
  }
  if (!kw.empty()) throw CommandStreamError(in.loc + "material: unexpected '" + kw + "'");
  return m;
}

TriangleCmd read_triangle(TextLine& in) {
  TriangleCmd t;
  t.xo = static_cast<int32_t>(in.read_int("xo", -32768, 32767));
  t.yo = static_cast<int32_t>(in.read_int("yo", -32768, 32767));
  std::string tok;
  while (in.ls >> tok) {
    if (tok == "|") continue;
    try {
      size_t used = 0;
      t.coef.push_back(std::stoll(tok, &used));
      if (used != tok.size()) throw std::invalid_argument(tok);
    } catch (const std::logic_error&) {
      throw CommandStreamError(in.loc + "tri: expected an integer coefficient, got '" + tok + "'");
    }
  }
  return t;
}

SpanCmd read_span(TextLine& in) {
  SpanCmd s;
  s.y = static_cast<int32_t>(in.read_int("y", 0, kField16));
  s.x0 = static_cast<int32_t>(in.read_int("x0", 0, kField16));
  s.length = static_cast<int32_t>(in.read_int("length", 1, kField16));
  // Then 'last' and, with host span setup, "| v d d2" per series.
  std::string tok;
  while (in.ls >> tok) {
    if (tok == "|") continue;
    if (tok == "last" && s.starts.empty() && !s.last_in_row) {
      s.last_in_row = true;
      continue;
    }
    try {
      size_t used = 0;
      s.starts.push_back(std::stoll(tok, &used));
      if (used != tok.size()) throw std::invalid_argument(tok);
    } catch (const std::logic_error&) {
      throw CommandStreamError(
          in.loc + "span: expected 'last', '|' or an integer start value, got '" + tok + "'");
    }
  }
  return s;
}

TableCmd read_table(TextLine& in) {
  TableCmd tb;
  tb.base = static_cast<uint32_t>(in.read_int("base", 0, kField16));
  std::string kw;
  tb.entries = in.read_list(&kw);
  if (kw == "material") {
    tb.per_material = true;
    std::string rest;
    if (in.ls >> rest)
      throw CommandStreamError(in.loc + "table: expected nothing after 'material', got '" + rest +
                               "'");
  } else if (!kw.empty()) {
    throw CommandStreamError(in.loc + "table: expected integers or 'material', got '" + kw + "'");
  }
  return tb;
}

Command read_command(TextLine& in) {
  if (in.op == "material") return read_material(in);
  if (in.op == "tri") return read_triangle(in);
  if (in.op == "span") return read_span(in);
  if (in.op == "table") return read_table(in);
  if (in.op == "end") return EndFrameCmd{};
  throw CommandStreamError(in.loc + "unknown command '" + in.op +
                           "'; expected material, tri, span, table or end");
}

}  // namespace

CommandStream CommandStream::read_text(std::istream& is, const std::string& source) {
  CommandStream cs;
  std::string line;
  size_t line_no = 0;
  bool have_header = false;
  while (std::getline(is, line)) {
    ++line_no;
    const std::string loc = source + ":" + std::to_string(line_no) + ": ";
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream ls(line);
    std::string op;
    if (!(ls >> op)) continue;
    TextLine in{ls, loc, op};
    if (!have_header) {
      cs.config = read_header(in, line, source, line_no);
      have_header = true;
      continue;
    }
    cs.commands.push_back(read_command(in));
    validate_command(cs.commands.back(), cs.config, Where{source, line_no, nullptr});
  }
  if (!have_header) throw CommandStreamError(source + ": empty command stream (no header line)");
  return cs;
}

void CommandStream::save(const std::string& path) const {
  std::ostringstream text;
  write_text(text);
  write_text_file(path, text.str());
}

CommandStream CommandStream::load(const std::string& path) {
  std::ifstream is(path);
  if (!is) throw CommandStreamError(path + ": cannot open command stream");
  return read_text(is, path);
}

std::string config_to_json(const UnitConfig& c) {
  nlohmann::json j;
  j["channels"] = c.channels;
  j["lights"] = c.lights;
  j["xy_bits"] = c.xy_bits;
  // Only when not the default: streams and build keys of screen-sized offsets stay as they were.
  if (c.offset_bits != UnitConfig::kMaxOffsetBits) j["offset_bits"] = c.offset_bits;
  j["coef"] = c.coef.to_string();
  j["series"] = c.series.to_string();
  j["spec_colour"] = c.spec_colour.to_string();
  j["out_bits"] = c.out_bits;
  if (!c.coef_term_iwl.empty()) j["coef_term_iwl"] = c.coef_term_iwl;
  j["port_words"] = c.port_words;
  j["tri_queue"] = c.tri_queue;
  j["lanes"] = c.lanes;
  // Only when not the default: streams and build keys of one-buffer units stay as they were.
  if (c.material_buffers != 1) j["material_buffers"] = c.material_buffers;
  // Likewise span_setup: unit-setup streams and build keys stay as they were.
  if (c.host_setup()) j["span_setup"] = to_string(c.span_setup);
  if (c.start_depth != UnitConfig::kStartDepth) j["start_depth"] = c.start_depth;
  if (c.diffuse_multiply()) j["diffuse_colour"] = to_string(c.diffuse_colour);
  if (c.combine_stages != 0) j["combine_stages"] = c.combine_stages;
  const SpecularConfig& sp = c.specular;
  j["specular"] = {{"kind", to_string(sp.kind)}, {"out", sp.out.to_string()}};
  for (const SpecularUnitDescriptor& u : specular_units()) {
    for (const SpecularField& f : u.fields) {
      auto& v = j["specular"][u.name][f.key];
      if (f.is_enum()) {
        v = f.text(sp);
      } else {
        v = f.get(sp);
      }
    }
  }
  return j.dump();
}

namespace {

// The one reader of UnitConfig JSON, shared by the command stream's header (config_from_json)
// and by config files (load_unit_config). It reads the fields present in a JSON object over a
// base config. Messages name the field by its JSON path behind `prefix` ("config." in a stream
// header, nothing in a file).
class ConfigJsonReader {
 public:
  // require_top: every top-level field must be present (a stream header is complete);
  // reject_unknown: a key that is no field is an error (a typo in a hand-written file).
  ConfigJsonReader(std::string prefix, bool require_top, bool reject_unknown)
      : prefix_(std::move(prefix)), require_top_(require_top), reject_unknown_(reject_unknown) {}

  void read(const nlohmann::json& j, UnitConfig& c) const {
    if (!j.is_object()) fail("", "expected a JSON object (a UnitConfig), got " + j.dump());
    // "derivation" is the annotation `shadesim config --json` writes beside the fields (how each
    // was derived); it is for people and never read.
    check_keys(j, "",
               {"channels", "lights", "xy_bits", "offset_bits", "coef", "series", "spec_colour",
                "out_bits", "coef_term_iwl", "port_words", "tri_queue", "lanes", "material_buffers",
                "span_setup", "start_depth", "diffuse_colour", "combine_stages", "specular",
                "derivation"});
    read_int(j, "", "channels", 1, 3, require_top_, c.channels);
    read_int(j, "", "lights", 1, 8, require_top_, c.lights);
    read_int(j, "", "xy_bits", 1, 16, require_top_, c.xy_bits);
    read_int(j, "", "offset_bits", 2, UnitConfig::kMaxOffsetBits, false, c.offset_bits);
    read_format(j, "", "coef", require_top_, c.coef);
    read_format(j, "", "series", require_top_, c.series);
    read_format(j, "", "spec_colour", require_top_, c.spec_colour);
    read_int(j, "", "out_bits", 1, 16, require_top_, c.out_bits);
    // Throughput structure: absent keys keep their defaults (streams written before it existed).
    read_int_list(j, "", "coef_term_iwl", -64, 64, c.coef_term_iwl);
    read_int(j, "", "port_words", 1, 8, false, c.port_words);
    read_int(j, "", "tri_queue", 1, 8, false, c.tri_queue);
    read_int(j, "", "lanes", 1, 4, false, c.lanes);
    read_int(j, "", "material_buffers", 1, 2, false, c.material_buffers);
    read_enum(j, "", "span_setup", false, parse_span_setup, c.span_setup);
    read_int(j, "", "start_depth", 1, 2, false, c.start_depth);
    read_enum(j, "", "diffuse_colour", false, parse_diffuse_colour, c.diffuse_colour);
    read_int(j, "", "combine_stages", 0, 2, false, c.combine_stages);
    if (!j.contains("specular")) {
      if (require_top_) fail("specular", "expected an object (missing)");
      return;
    }
    const auto& s = j.at("specular");
    if (!s.is_object()) fail("specular", "expected an object, got " + s.dump());
    std::vector<std::string> specular_keys = {"kind", "out"};
    for (const SpecularUnitDescriptor& u : specular_units()) {
      if (!u.fields.empty()) specular_keys.emplace_back(u.name);
    }
    check_keys(s, "specular.", specular_keys);
    SpecularConfig& sp = c.specular;
    read_enum(s, "specular.", "kind", require_top_, parse_specular_unit, sp.kind);
    read_format(s, "specular.", "out", require_top_, sp.out);
    // Unit fields (model/specular_units.h): absent keys keep their base values (streams written
    // before the units existed); present ones must be integers / names (validate() then checks
    // their ranges).
    constexpr int kLo = -1000000, kHi = 1000000;
    for (const SpecularUnitDescriptor& u : specular_units()) {
      if (u.fields.empty()) continue;
      std::vector<std::string> keys;
      for (const SpecularField& f : u.fields) keys.emplace_back(f.key);
      const auto* o = unit_object(s, u.name, keys);
      if (!o) continue;
      const std::string at = std::string("specular.") + u.name + ".";
      for (const SpecularField& f : u.fields) {
        int v = f.get(sp);
        if (f.is_enum()) {
          if (const auto* text = read_string(*o, at, f.key, false))
            v = f.parse(*text, prefix_ + at + f.key);
        } else {
          read_int(*o, at, f.key, kLo, kHi, false, v);
        }
        f.set(sp, v);
      }
    }
  }

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& msg) const {
    std::string name = prefix_ + path;
    if (path.empty() && !name.empty() && name.back() == '.') name.pop_back();  // the whole object
    throw std::invalid_argument(name.empty() ? msg : name + ": " + msg);
  }

  void check_keys(const nlohmann::json& o, const std::string& at,
                  const std::vector<std::string>& known) const {
    if (!reject_unknown_) return;
    for (const auto& item : o.items()) {
      bool found = false;
      std::string names;
      for (const std::string& k : known) {
        found = found || item.key() == k;
        names += (names.empty() ? "" : ", ") + k;
      }
      if (!found) fail(at + item.key(), "unknown field; expected one of " + names);
    }
  }

  // An integer field: must be a JSON integer (not 12.9, not true) within [lo, hi].
  // An optional array of integers (absent keeps the base value).
  void read_int_list(const nlohmann::json& o, const std::string& at, const char* key, int lo,
                     int hi, std::vector<int>& v) const {
    if (!o.contains(key)) return;
    const auto& x = o.at(key);
    if (!x.is_array()) fail(at + key, "expected an array of integers, got " + x.dump());
    std::vector<int> out;
    for (size_t i = 0; i < x.size(); ++i) {
      const auto& e = x[i];
      const std::string name = at + key + "[" + std::to_string(i) + "]";
      if (!e.is_number_integer()) fail(name, "expected an integer, got " + e.dump());
      const auto n = e.get<int64_t>();
      if (n < lo || n > hi) {
        fail(name,
             "expected " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " + e.dump());
      }
      out.push_back(static_cast<int>(n));
    }
    v = out;
  }

  void read_int(const nlohmann::json& o, const std::string& at, const char* key, int lo, int hi,
                bool required, int& v) const {
    if (!o.contains(key)) {
      if (required) fail(at + key, "missing");
      return;
    }
    const auto& x = o.at(key);
    if (!x.is_number_integer()) fail(at + key, "expected an integer, got " + x.dump());
    const auto n = x.get<int64_t>();
    if (n < lo || n > hi) {
      fail(at + key,
           "expected " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " + x.dump());
    }
    v = static_cast<int>(n);
  }

  // A string field; nullptr when absent and not required.
  const std::string* read_string(const nlohmann::json& o, const std::string& at, const char* key,
                                 bool required) const {
    if (!o.contains(key)) {
      if (required) fail(at + key, "expected a string (missing)");
      return nullptr;
    }
    const auto& x = o.at(key);
    if (!x.is_string()) fail(at + key, "expected a string, got " + x.dump());
    return x.get_ptr<const std::string*>();
  }

  void read_format(const nlohmann::json& o, const std::string& at, const char* key, bool required,
                   FixedFormat& v) const {
    if (const auto* text = read_string(o, at, key, required))
      v = parse_fixed_format(*text, prefix_ + at + key);
  }

  template <typename E>
  void read_enum(const nlohmann::json& o, const std::string& at, const char* key, bool required,
                 E (*parse)(const std::string&, const std::string&), E& v) const {
    if (const auto* text = read_string(o, at, key, required)) v = parse(*text, prefix_ + at + key);
  }

  const nlohmann::json* unit_object(const nlohmann::json& s, const char* unit,
                                    const std::vector<std::string>& known) const {
    if (!s.contains(unit)) return nullptr;
    const auto& o = s.at(unit);
    if (!o.is_object())
      fail(std::string("specular.") + unit, "expected an object, got " + o.dump());
    check_keys(o, std::string("specular.") + unit + ".", known);
    return &o;
  }

  std::string prefix_;
  bool require_top_;
  bool reject_unknown_;
};

}  // namespace

namespace {

// A stream header's UnitConfig JSON. A syntax error is named at `syntax_at(error)` (the file,
// line and column) with what was expected there, never by nlohmann's "[json.exception...]" text;
// any other error by `source` (a prefix ending in ": ") and the field.
UnitConfig header_config(const std::string& text, const std::string& source,
                         const std::function<std::string(const JsonTextError&)>& syntax_at) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    const JsonTextError error = describe_json_error(text, e);
    throw CommandStreamError(syntax_at(error) +
                             "the header's config (a UnitConfig JSON object): " + error.reason);
  }
  UnitConfig c;
  try {
    // A stream header is complete; keys it does not know are ignored (newer writers).
    ConfigJsonReader("config.", true, false).read(j, c);
    c.specular.validate();
    c.validate();
  } catch (const nlohmann::json::exception& e) {
    throw CommandStreamError(source + "config: " + describe_json_error(text, e).reason);
  } catch (const std::invalid_argument& e) {
    throw CommandStreamError(source + e.what());
  }
  return c;
}

}  // namespace

UnitConfig config_from_json(const std::string& text, const std::string& source) {
  // A text of its own: a syntax error is at "config:LINE:COLUMN" of it.
  return header_config(text, source, [&](const JsonTextError& error) {
    return source + "config" + error.place + ": ";
  });
}

UnitConfig overlay_unit_config(const std::string& json_object, const UnitConfig& base,
                               const std::string& source) {
  return parse_unit_config(json_object, source, base);
}

UnitConfig parse_unit_config(const std::string& text, const std::string& source,
                             const UnitConfig& base) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    const JsonTextError error = describe_json_error(text, e);
    throw UnitConfigFileError(source + error.place + ": JSON syntax error: " + error.reason);
  }
  UnitConfig c = base;
  try {
    ConfigJsonReader("", false, true).read(j, c);
    c.specular.validate();
    c.validate();
  } catch (const nlohmann::json::exception& e) {
    throw UnitConfigFileError(source + ": " + e.what());
  } catch (const std::invalid_argument& e) {
    throw UnitConfigFileError(source + ": " + e.what());
  }
  return c;
}

UnitConfig load_unit_config(const std::string& path, const UnitConfig& base) {
  std::ifstream is(path, std::ios::binary);
  if (!is || std::filesystem::is_directory(path)) {
    throw UnitConfigFileError(path + ": cannot open config file");
  }
  std::ostringstream buf;
  buf << is.rdbuf();
  return parse_unit_config(buf.str(), path, base);
}

}  // namespace shadesim
