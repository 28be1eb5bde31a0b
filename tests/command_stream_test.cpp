// Command stream: binary and text round trips, and clear errors on malformed streams.
#include "model/command_stream.h"

#include <gtest/gtest.h>

#include <array>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "model/coef_packing.h"

namespace shadesim {
namespace {

UnitConfig rgb_two_lights() {
  UnitConfig c;
  c.channels = 3;
  c.lights = 2;
  return c;
}

CommandStream sample_stream(const UnitConfig& c, uint64_t seed) {
  std::mt19937_64 rng(seed);
  CommandStream cs;
  cs.config = c;
  MaterialCmd m;
  for (int i = 0; i < c.channels; ++i)
    m.ambient.push_back(static_cast<int64_t>(rng() % 1000000) - 500000);
  for (int i = 0; i < c.lights * c.channels; ++i)
    m.spec_colour.push_back(static_cast<int64_t>(rng() % 4096));
  m.exponent = int64_t{37} << kExponentFracBits;
  m.unit_params = {1, -2, 3};
  m.gate_only = 2;  // light 1's diffuse series gates only
  cs.commands.emplace_back(m);
  cs.commands.emplace_back(TableCmd{5, {1, 2, 3, 255}});
  for (int tri = 0; tri < 3; ++tri) {
    TriangleCmd t;
    t.xo = static_cast<int32_t>(rng() % 4096) - 100;
    t.yo = -static_cast<int32_t>(rng() % 50);
    std::uniform_int_distribution<int64_t> coef(c.coef.raw_min(), c.coef.raw_max());
    for (int i = 0; i < c.series_per_triangle() * kTermsPerSeries; ++i) t.coef.push_back(coef(rng));
    cs.commands.emplace_back(t);
    SpanCmd s;
    s.y = static_cast<int32_t>(rng() % 4096);
    s.x0 = static_cast<int32_t>(rng() % 2048);
    s.length = 1 + static_cast<int32_t>(rng() % 2048);
    s.last_in_row = tri == 1;
    cs.commands.emplace_back(s);
  }
  cs.commands.emplace_back(EndFrameCmd{});
  return cs;
}

TEST(CommandStream, BinaryRoundTripIsIdentity) {
  const auto c = rgb_two_lights();
  const auto cs = sample_stream(c, 1);
  const auto words = cs.encode();
  const auto back = CommandStream::decode(words, c, "<test>");
  EXPECT_EQ(back.encode(), words);
  ASSERT_EQ(back.commands.size(), cs.commands.size());
  const auto& t = std::get<TriangleCmd>(back.commands[2]);
  const auto& t0 = std::get<TriangleCmd>(cs.commands[2]);
  EXPECT_EQ(t.xo, t0.xo);
  EXPECT_EQ(t.yo, t0.yo);  // negative origins survive the 16-bit field
  EXPECT_EQ(t.coef, t0.coef);
  EXPECT_EQ(std::get<MaterialCmd>(back.commands[0]).gate_only, 2u);
}

TEST(CommandStream, TextRoundTripKeepsConfigAndWords) {
  const auto c = rgb_two_lights();
  const auto cs = sample_stream(c, 2);
  std::stringstream ss;
  cs.write_text(ss);
  const auto back = CommandStream::read_text(ss, "<text>");
  EXPECT_EQ(back.encode(), cs.encode());
  EXPECT_EQ(back.config.to_string(), c.to_string());
  EXPECT_EQ(std::get<MaterialCmd>(back.commands[0]).gate_only, 2u);
}

TEST(CommandStream, MaterialGateOnlyMaskIsHeaderBits31To16) {
  CommandStream cs;
  cs.config.lights = 3;
  MaterialCmd m;
  m.ambient = {0};
  m.spec_colour = {0, 0, 0};
  m.gate_only = 5;
  cs.commands.emplace_back(m);
  const auto w = cs.encode();
  EXPECT_EQ(w[0] >> 56, 0x01u);
  EXPECT_EQ((w[0] >> 16) & 0xFFFF, 5u);
  EXPECT_EQ(w[0] & 0xFFFF, 5u);  // 1 ambient + 3 spec_colour + exponent
  // A bit beyond the unit's lights is an error naming the field.
  const std::vector<uint64_t> bad = {
      (uint64_t{0x01} << 56) | (uint64_t{8} << 16) | 5, 0, 0, 0, 0, 0};
  try {
    CommandStream::decode(bad, cs.config, "dump.bin");
    FAIL();
  } catch (const CommandStreamError& e) {
    EXPECT_NE(std::string(e.what()).find("material.gate_only = 8"), std::string::npos) << e.what();
  }
}

// Diffuse colour multiply: the MATERIAL's payload is ambient, spec_colour, then diffuse_colour
// (lights x channels words), then the exponent; both forms round-trip it, the JSON header keeps
// the knob, and a MATERIAL without the colours (or with a gate-only light) is refused.
TEST(CommandStream, DiffuseColourFollowsSpecColourAndRoundTrips) {
  UnitConfig c = rgb_two_lights();
  c.diffuse_colour = DiffuseColour::kMultiply;
  CommandStream cs;
  cs.config = c;
  MaterialCmd m;
  m.ambient = {1, 2, 3};
  m.spec_colour = {10, 11, 12, 13, 14, 15};
  m.diffuse_colour = {20, 21, 22, 23, 24, 25};
  m.exponent = int64_t{8} << kExponentFracBits;
  cs.commands.emplace_back(m);
  const auto w = cs.encode();
  ASSERT_EQ(w.size(), 1u + 3 + 6 + 6 + 1);
  EXPECT_EQ(w[0] & 0xFFFF, 16u);
  EXPECT_EQ(w[1 + 3 + 6], 20u);  // the first diffuse colour right after the specular ones
  EXPECT_EQ(w[1 + 3 + 6 + 6], static_cast<uint64_t>(m.exponent));
  const auto back = CommandStream::decode(w, c, "<test>");
  EXPECT_EQ(std::get<MaterialCmd>(back.commands[0]).diffuse_colour, m.diffuse_colour);
  EXPECT_EQ(std::get<MaterialCmd>(back.commands[0]).exponent, m.exponent);
  std::stringstream ss;
  cs.write_text(ss);
  const auto text = CommandStream::read_text(ss, "<text>");
  EXPECT_TRUE(text.config.diffuse_multiply());
  EXPECT_EQ(text.encode(), w);

  CommandStream missing = cs;
  std::get<MaterialCmd>(missing.commands[0]).diffuse_colour.clear();
  try {
    missing.validate("s.txt");
    FAIL();
  } catch (const CommandStreamError& e) {
    EXPECT_NE(std::string(e.what()).find("material.diffuse_colour: expected 6 values, got 0"),
              std::string::npos)
        << e.what();
  }
  CommandStream gated = cs;
  std::get<MaterialCmd>(gated.commands[0]).gate_only = 1;
  EXPECT_THROW(gated.validate("s.txt"), CommandStreamError);
}

TEST(CommandStream, HeaderWordLayoutMatchesDocumentation) {
  CommandStream cs;
  cs.commands.emplace_back(SpanCmd{7, 9, 300, true});
  const auto w = cs.encode();
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0] >> 56, 0x03u);
  EXPECT_EQ((w[0] >> 55) & 1, 1u);
  EXPECT_EQ((w[0] >> 32) & 0xFFFF, 7u);
  EXPECT_EQ((w[0] >> 16) & 0xFFFF, 9u);
  EXPECT_EQ(w[0] & 0xFFFF, 300u);
}

TEST(CommandStream, PerMaterialTableIsHeaderBit55AndRoundTrips) {
  CommandStream cs;
  cs.commands.emplace_back(TableCmd{3, {7, 8}, true});
  cs.commands.emplace_back(TableCmd{4, {9}, false});
  const auto w = cs.encode();
  ASSERT_EQ(w.size(), 5u);
  EXPECT_EQ(w[0] >> 56, 0x04u);
  EXPECT_EQ((w[0] >> 55) & 1, 1u);
  EXPECT_EQ((w[0] >> 16) & 0xFFFF, 3u);
  EXPECT_EQ(w[0] & 0xFFFF, 2u);
  EXPECT_EQ((w[3] >> 55) & 1, 0u);
  const CommandStream back = CommandStream::decode(w, cs.config, "t.bin");
  ASSERT_EQ(back.commands.size(), 2u);
  EXPECT_TRUE(std::get<TableCmd>(back.commands[0]).per_material);
  EXPECT_FALSE(std::get<TableCmd>(back.commands[1]).per_material);
  std::stringstream text;
  cs.write_text(text);
  EXPECT_NE(text.str().find("table 3 7 8 material\n"), std::string::npos) << text.str();
  const CommandStream again = CommandStream::read_text(text, "t.cmd");
  EXPECT_EQ(again.encode(), w);
}

// An empty TABLE is a header alone (count 0): it round-trips through binary and text, and the
// word after it is the next command's header.
TEST(CommandStream, EmptyTableIsAHeaderAloneAndRoundTrips) {
  CommandStream cs;
  cs.commands.emplace_back(TableCmd{5, {}, true});
  cs.commands.emplace_back(TableCmd{6, {}, false});
  cs.commands.emplace_back(EndFrameCmd{});
  const auto w = cs.encode();
  ASSERT_EQ(w.size(), 3u);
  EXPECT_EQ(w[0] & 0xFFFF, 0u);
  EXPECT_EQ((w[1] >> 16) & 0xFFFF, 6u);
  EXPECT_EQ(w[2] >> 56, 0x0Fu);
  const CommandStream back = CommandStream::decode(w, cs.config, "t.bin");
  ASSERT_EQ(back.commands.size(), 3u);
  EXPECT_TRUE(std::get<TableCmd>(back.commands[0]).entries.empty());
  EXPECT_EQ(std::get<TableCmd>(back.commands[1]).base, 6u);
  std::stringstream text;
  cs.write_text(text);
  const CommandStream again = CommandStream::read_text(text, "t.cmd");
  EXPECT_EQ(again.encode(), w) << text.str();
}

void expect_text_error(const std::string& body, const std::string& needle) {
  std::stringstream ss("shadesim-commands 2 " + config_to_json(UnitConfig{}) + "\n" + body);
  try {
    CommandStream::read_text(ss, "bad.cmd");
    FAIL() << "accepted: " << body;
  } catch (const CommandStreamError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("bad.cmd:2:"), std::string::npos) << msg;
    EXPECT_NE(msg.find(needle), std::string::npos) << msg;
  }
}

TEST(CommandStream, TextErrorsNameLineAndExpectation) {
  expect_text_error("tri 0 0 | 1 2 3\n", "expected 12 values, got 3");
  expect_text_error("span 1 2\n", "expected an integer for length");
  expect_text_error("span 1 2 0\n", "length = 0 is outside 1..65535");
  expect_text_error("span 1 5000 3\n", "xy_bits");
  expect_text_error("span 1 2 3 first\n", "expected 'last'");
  expect_text_error("frobnicate\n", "unknown command 'frobnicate'");
  expect_text_error("material ambient 1 spec_colour 1 exponent 99999999999 params\n", "exponent");
  expect_text_error("material ambient 1 2 spec_colour 1 exponent 5 params\n", "material.ambient");
  expect_text_error("tri 0 0 | 1 2 3 4 5 x\n", "expected an integer coefficient");
  expect_text_error("material ambient 1 spec_colour 1 exponent 5 params gate_only 2\n",
                    "material.gate_only = 2: expected a mask of the unit's 1 lights");
  expect_text_error("material ambient 1 spec_colour 1 exponent 5 params gate_only\n",
                    "expected an integer for gate_only");
  expect_text_error("table 0 1 2 shared\n", "table: expected integers or 'material'");
  expect_text_error("table 0 1 2 material 3\n", "expected nothing after 'material'");
}

// Version 1 headers wrote a saturating format without a suffix; version 2 reads a suffix-less
// format as sc_fix does (truncate, wrap). A saved version-1 stream keeps its meaning, and a
// version this reader does not know is refused by name.
TEST(CommandStream, Version1FormatsWithoutSuffixStillSaturate) {
  nlohmann::json j = nlohmann::json::parse(config_to_json(UnitConfig{}));
  j["series"] = "s4.28";
  j["coef"] = "s4.32:rnd";
  j["spec_colour"] = "u1.12:wrap";
  const std::string unit = j.dump();
  const auto read = [&](int version) {
    std::stringstream ss("shadesim-commands " + std::to_string(version) + " " + unit + "\nend\n");
    return CommandStream::read_text(ss, "v.cmd").config;
  };
  const UnitConfig v1 = read(1);
  const UnitConfig v2 = read(2);
  EXPECT_EQ(v1.series.overflow, Overflow::kSaturate);
  EXPECT_EQ(v1.coef.overflow, Overflow::kSaturate);
  EXPECT_EQ(v1.coef.quant, Quantization::kRoundNearest);
  EXPECT_EQ(v1.spec_colour.overflow, Overflow::kWrap);  // written, so kept
  EXPECT_EQ(v2.series.overflow, Overflow::kWrap);
  EXPECT_EQ(v2.coef.overflow, Overflow::kWrap);
  // What this version writes reads back the same.
  std::stringstream out;
  CommandStream written;
  written.config = v1;
  written.write_text(out);
  EXPECT_EQ(out.str().rfind("shadesim-commands 2 ", 0), 0u) << out.str();
  EXPECT_EQ(CommandStream::read_text(out, "w.cmd").config.to_string(), v1.to_string());
  std::stringstream v3("shadesim-commands 3 " + unit + "\n");
  try {
    CommandStream::read_text(v3, "v3.cmd");
    ADD_FAILURE() << "accepted version 3";
  } catch (const CommandStreamError& e) {
    EXPECT_NE(std::string(e.what()).find("expected 1 or 2"), std::string::npos) << e.what();
  }
}

TEST(CommandStream, MissingHeaderAndEmptyStreamAreErrors) {
  std::stringstream a("span 1 2 3\n");
  EXPECT_THROW(CommandStream::read_text(a, "a.cmd"), CommandStreamError);
  std::stringstream b("");
  EXPECT_THROW(CommandStream::read_text(b, "b.cmd"), CommandStreamError);
  std::stringstream c("shadesim-commands 2 {\"channels\": 2}\n");
  EXPECT_THROW(CommandStream::read_text(c, "c.cmd"), CommandStreamError);
}

// A malformed header JSON (6 of 400 fuzzed inputs) is named by file, line and column
// with what was expected there, not by nlohmann's "[json.exception.parse_error.101]" text. The
// columns are counted by hand: "shadesim-commands 2 " is 20 characters, so the JSON's '{' is
// column 21.
TEST(CommandStream, MalformedHeaderJsonNamesFileColumnAndExpectation) {
  const std::vector<std::array<std::string, 3>> cases = {
      // {header line, where, what was expected}
      {R"(shadesim-commands 2 {"channels":1,,"lights":1})",
       "h.cmd:1:35:", "expected string literal"},                                // the second ','
      {R"(shadesim-commands 2 {"channels": 1)", "h.cmd:1:35:", "expected '}'"},  // end of line
      {R"(shadesim-commands 2   {"lights" 1})", "h.cmd:1:33:", "expected ':'"},  // the 1
      {R"(shadesim-commands 2 {"channels": 1e999})", "h.cmd:1:34:", "1e999"},
      {"shadesim-commands 2", "h.cmd:1:20:", "expected the unit's config JSON"},
  };
  for (const auto& [header, where, expected] : cases) {
    std::stringstream ss(header + "\nspan 1 2 3\n");
    try {
      CommandStream::read_text(ss, "h.cmd");
      ADD_FAILURE() << "accepted: " << header;
    } catch (const CommandStreamError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(where, 0), 0u) << header << "\n" << msg;
      EXPECT_NE(msg.find(expected), std::string::npos) << header << "\n" << msg;
      EXPECT_EQ(msg.find("json.exception"), std::string::npos) << msg;
    }
  }
}

TEST(CommandStream, BinaryErrorsNameWordIndex) {
  const UnitConfig c;
  // Truncated triangle payload.
  std::vector<uint64_t> words = {(uint64_t{0x02} << 56) | 12, 1, 2, 3};
  try {
    CommandStream::decode(words, c, "dump.bin");
    FAIL();
  } catch (const CommandStreamError& e) {
    EXPECT_NE(std::string(e.what()).find("dump.bin:word 0"), std::string::npos) << e.what();
  }
  // Unknown opcode at word 1.
  words = {uint64_t{0x0F} << 56, uint64_t{0x7E} << 56};
  try {
    CommandStream::decode(words, c, "dump.bin");
    FAIL();
  } catch (const CommandStreamError& e) {
    EXPECT_NE(std::string(e.what()).find("word 1: unknown opcode 0x7e"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace shadesim

namespace shadesim {
namespace {

// The throughput structure travels with the stream; absent keys mean 1 (older streams), and a
// value the hardware cannot have is an error naming the field.
TEST(CommandStream, ThroughputStructureRoundTripsAndDefaults) {
  UnitConfig c;
  c.port_words = 4;
  c.tri_queue = 3;
  c.lanes = 4;
  c.material_buffers = 2;
  const UnitConfig back = config_from_json(config_to_json(c), "t: ");
  EXPECT_EQ(back.port_words, 4);
  EXPECT_EQ(back.tri_queue, 3);
  EXPECT_EQ(back.lanes, 4);
  EXPECT_EQ(back.material_buffers, 2);
  // Written only when not 1, so a one-buffer unit's stream header is what it was.
  EXPECT_EQ(config_to_json(UnitConfig{}).find("material_buffers"), std::string::npos);
  for (const char* bad : {"0", "3", "1.5"}) {
    std::string json = config_to_json(UnitConfig{});
    json.insert(1, std::string(R"("material_buffers":)") + bad + ",");
    try {
      config_from_json(json, "bad: ");
      ADD_FAILURE() << "accepted material_buffers " << bad;
    } catch (const CommandStreamError& e) {
      EXPECT_NE(std::string(e.what()).find("material_buffers"), std::string::npos) << e.what();
    }
  }
  const UnitConfig old = config_from_json(
      R"({"channels":1,"lights":1,"xy_bits":12,"coef":"s4.32:rnd:sat","series":"s4.28",)"
      R"("spec_colour":"u1.12:rnd:sat","out_bits":8,"specular":{"kind":"ideal","out":"u1.16:sat"}})",
      "old: ");
  EXPECT_EQ(old.port_words, 1);
  EXPECT_EQ(old.tri_queue, 1);
  EXPECT_EQ(old.lanes, 1);
  EXPECT_EQ(old.material_buffers, 1);
  for (const char* bad : {R"("port_words":3)", R"("port_words":2.5)", R"("tri_queue":0)",
                          R"("tri_queue":9)", R"("lanes":3)", R"("lanes":0)", R"("lanes":8)"}) {
    std::string json = config_to_json(UnitConfig{});
    const std::string key = std::string(bad).substr(0, std::string(bad).find(':'));
    const size_t at = json.find(key);
    ASSERT_NE(at, std::string::npos) << key;
    const size_t end = json.find_first_of(",}", at);
    json.replace(at, end - at, bad);
    try {
      config_from_json(json, "bad: ");
      ADD_FAILURE() << "accepted " << bad;
    } catch (const CommandStreamError& e) {
      EXPECT_NE(std::string(e.what()).find(key.substr(1, key.size() - 2)), std::string::npos)
          << e.what();
    }
  }
}

UnitConfig packed_grey() {
  UnitConfig c;
  c.coef = parse_fixed_format("s2.15:rnd:wrap", "test");
  c.series = parse_fixed_format("s2.14:wrap", "test");
  c.coef_term_iwl = {2, 1, 1, 0, -1, -2};  // widths 17 16 16 15 14 13
  return c;
}

TEST(CoefPacking, LayoutFillsWordsWithoutStraddling) {
  // Worked by hand: series 0 T0..T3 fill word 0 exactly (17+16+16+15 = 64); T4, T5 start
  // word 1 (lsb 0, 14), then series 1 T0, T1 (lsb 27, 44: 60 bits used); T2 (16) does not fit
  // the 4 bits left, so word 2 takes T2..T5 at lsb 0, 16, 31, 45.
  const CoefLayout l = CoefLayout::of(packed_grey());
  ASSERT_EQ(l.slots.size(), 12u);
  const std::vector<std::pair<int, int>> want = {{0, 0}, {0, 17}, {0, 33}, {0, 49},
                                                 {1, 0}, {1, 14}, {1, 27}, {1, 44},
                                                 {2, 0}, {2, 16}, {2, 31}, {2, 45}};
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(l.slots[i].word, want[i].first) << i;
    EXPECT_EQ(l.slots[i].lsb, want[i].second) << i;
  }
  EXPECT_EQ(l.words, 3);
  // The default 36-bit terms: one per word.
  EXPECT_EQ(CoefLayout::of(UnitConfig{}).words, 12);
}

TEST(CoefPacking, PackedStreamRoundTripsAtEveryTermsLimits) {
  const UnitConfig c = packed_grey();
  CommandStream cs;
  cs.config = c;
  TriangleCmd t;
  t.xo = 3;
  t.yo = -4;
  for (int i = 0; i < 12; ++i) {
    const FixedFormat f = c.coef_term(i % kTermsPerSeries);
    t.coef.push_back(i % 3 == 0 ? f.raw_min() : i % 3 == 1 ? f.raw_max() : -1);
  }
  cs.commands.emplace_back(t);
  cs.validate("<test>");
  const auto words = cs.encode();
  ASSERT_EQ(words.size(), 4u);  // header + 3 payload words
  EXPECT_EQ(CommandWord{words[0]}.count(), 3u);
  const auto back = CommandStream::decode(words, c, "<test>");
  EXPECT_EQ(std::get<TriangleCmd>(back.commands[0]).coef, t.coef);
  // A value beyond its term's format is a validation error naming the term.
  t.coef[3] = c.coef_term(3).raw_max() + 1;
  cs.commands = {t};
  try {
    cs.validate("<test>");
    ADD_FAILURE() << "accepted a T3 beyond its format";
  } catch (const CommandStreamError& e) {
    EXPECT_NE(std::string(e.what()).find("T3"), std::string::npos) << e.what();
  }
  // A header whose count is not the layout's is an error naming the expected count.
  auto bad = words;
  bad[0] = CommandWord::triangle(3, -4, 12).bits;
  bad.resize(13, 0);
  try {
    CommandStream::decode(bad, c, "<test>");
    ADD_FAILURE() << "accepted a 12-word triangle in a 3-word layout";
  } catch (const CommandStreamError& e) {
    EXPECT_NE(std::string(e.what()).find("expected 3 payload words"), std::string::npos)
        << e.what();
  }
}

TEST(CoefPacking, TermFormatsRoundTripThroughJsonAndAreChecked) {
  const UnitConfig c = packed_grey();
  EXPECT_EQ(config_from_json(config_to_json(c), "t: ").coef_term_iwl, c.coef_term_iwl);
  UnitConfig wide = c;
  wide.coef_term_iwl[1] = 3;  // more than coef's 2 integer bits
  EXPECT_THROW(wide.validate(), std::invalid_argument);
  UnitConfig few = c;
  few.coef_term_iwl.pop_back();
  EXPECT_THROW(few.validate(), std::invalid_argument);
  // Narrowed terms saturate; a term with coef's integer bits keeps coef's wrap.
  EXPECT_EQ(c.coef_term(0).overflow, Overflow::kWrap);
  EXPECT_EQ(c.coef_term(3).overflow, Overflow::kSaturate);
  EXPECT_EQ(c.coef_term(5).wl, 13);
}

}  // namespace
}  // namespace shadesim
