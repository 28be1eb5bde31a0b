// load_unit_config: a UnitConfig JSON file over a base config, with errors naming the file and
// the field (or the line and column of a JSON syntax error).
#include "model/unit_config_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "model/command_stream.h"

namespace shadesim {
namespace {

class UnitConfigFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("shadesim_unit_config_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const {
    std::string path = (dir_ / name).string();  // returned: moved
    std::ofstream(path) << text;
    return path;
  }

  // The message of the UnitConfigFileError that loading `text` throws ("" if none).
  std::string error_of(const std::string& text, const UnitConfig& base = {}) const {
    const std::string path = write("bad.json", text);
    try {
      (void)load_unit_config(path, base);
    } catch (const UnitConfigFileError& e) {
      std::string msg = e.what();  // returned: moved
      EXPECT_NE(msg.find(path), std::string::npos) << "the error must name the file: " << msg;
      return msg;
    }
    ADD_FAILURE() << "expected an error for " << text;
    return "";
  }

  std::filesystem::path dir_;
};

TEST_F(UnitConfigFile, FullRoundTripThroughConfigToJson) {
  UnitConfig c;  // every field away from its default
  c.channels = 3;
  c.lights = 2;
  c.xy_bits = 11;
  c.coef = FixedFormat{30, 6, true, Quantization::kTruncate, Overflow::kSaturate};
  c.series = FixedFormat{27, 5, true, Quantization::kRoundNearest, Overflow::kSaturate};
  c.spec_colour = FixedFormat{11, 1, false, Quantization::kTruncate, Overflow::kSaturate};
  c.out_bits = 10;
  c.specular.kind = SpecularUnitKind::kSchlick;
  c.specular.out = FixedFormat{14, 2, false, Quantization::kRoundNearest, Overflow::kSaturate};
  c.specular.lut = {
      7, 9, 3, LutIndex::kNearest, LutAddressing::kShared, 5, FitObjective::kAbsolute};
  c.specular.schlick = {13, 20, UnitTiming::kPipelined, FitObjective::kEpicentre};
  c.specular.wpow = {8, 12, UnitTiming::kIterative, 1, FitObjective::kAbsolute};
  const UnitConfig d = load_unit_config(write("full.json", config_to_json(c)));
  EXPECT_EQ(d.channels, 3);
  EXPECT_EQ(d.lights, 2);
  EXPECT_EQ(d.xy_bits, 11);
  auto same_format = [](const FixedFormat& a, const FixedFormat& b) {
    return a.wl == b.wl && a.iwl == b.iwl && a.is_signed == b.is_signed && a.quant == b.quant &&
           a.overflow == b.overflow;
  };
  EXPECT_TRUE(same_format(d.coef, c.coef)) << d.coef.to_string();
  EXPECT_TRUE(same_format(d.series, c.series)) << d.series.to_string();
  EXPECT_TRUE(same_format(d.spec_colour, c.spec_colour)) << d.spec_colour.to_string();
  EXPECT_TRUE(same_format(d.specular.out, c.specular.out)) << d.specular.out.to_string();
  EXPECT_EQ(d.out_bits, 10);
  EXPECT_EQ(d.specular.kind, SpecularUnitKind::kSchlick);
  EXPECT_EQ(d.specular.lut.addr_bits, 7);
  EXPECT_EQ(d.specular.lut.entry_bits, 9);
  EXPECT_EQ(d.specular.lut.interp_bits, 3);
  EXPECT_EQ(d.specular.lut.index, LutIndex::kNearest);
  EXPECT_EQ(d.specular.lut.addressing, LutAddressing::kShared);
  EXPECT_EQ(d.specular.lut.shared_range_log2, 5);
  EXPECT_EQ(d.specular.lut.fit, FitObjective::kAbsolute);
  EXPECT_EQ(d.specular.schlick.quotient_bits, 13);
  EXPECT_EQ(d.specular.schlick.operand_bits, 20);
  EXPECT_EQ(d.specular.schlick.timing, UnitTiming::kPipelined);
  EXPECT_EQ(d.specular.schlick.fit, FitObjective::kEpicentre);
  EXPECT_EQ(d.specular.wpow.max_m, 8);
  EXPECT_EQ(d.specular.wpow.base_bits, 12);
  EXPECT_EQ(d.specular.wpow.timing, UnitTiming::kIterative);
  EXPECT_EQ(d.specular.wpow.fit, FitObjective::kAbsolute);
}

TEST_F(UnitConfigFile, OmittedFieldsKeepTheBase) {
  UnitConfig base;
  base.channels = 3;
  base.lights = 2;
  base.specular.kind = SpecularUnitKind::kWpow;
  base.specular.wpow.base_bits = 14;
  const UnitConfig d = load_unit_config(
      write("part.json", R"({"series": "s4.30", "specular": {"wpow": {"max_m": 8}}})"), base);
  EXPECT_EQ(d.series.wl, 34);  // from the file
  EXPECT_EQ(d.series.iwl, 4);
  EXPECT_EQ(d.series.overflow, Overflow::kWrap);  // "s4.30" wraps, as sc_fix does (no :sat)
  EXPECT_EQ(d.specular.wpow.max_m, 8);
  EXPECT_EQ(d.channels, 3);  // from the base
  EXPECT_EQ(d.lights, 2);
  EXPECT_EQ(d.specular.kind, SpecularUnitKind::kWpow);
  EXPECT_EQ(d.specular.wpow.base_bits, 14);
  EXPECT_EQ(d.coef.wl, 36);
  // An empty object is the base itself; the default base is UnitConfig{}.
  const UnitConfig e = load_unit_config(write("empty.json", "{}"));
  EXPECT_EQ(e.to_string(), UnitConfig{}.to_string());
}

TEST_F(UnitConfigFile, UnknownKeysAreErrorsNamingThePath) {
  const std::string top = error_of(R"({"seires": "s4.30"})");
  EXPECT_NE(top.find("seires"), std::string::npos) << top;
  EXPECT_NE(top.find("unknown field"), std::string::npos) << top;
  EXPECT_NE(top.find("series"), std::string::npos) << "should list the known fields: " << top;
  const std::string nested = error_of(R"({"specular": {"wpow": {"maxm": 8}}})");
  EXPECT_NE(nested.find("specular.wpow.maxm"), std::string::npos) << nested;
}

TEST_F(UnitConfigFile, WrongTypesAndRangesNameTheFieldAndWhatWasExpected) {
  const std::string lights = error_of(R"({"lights": "2"})");
  EXPECT_NE(lights.find("lights: expected an integer"), std::string::npos) << lights;
  const std::string real = error_of(R"({"xy_bits": 11.5})");
  EXPECT_NE(real.find("xy_bits: expected an integer"), std::string::npos) << real;
  const std::string coef = error_of(R"({"coef": 36})");
  EXPECT_NE(coef.find("coef: expected a string"), std::string::npos) << coef;
  const std::string spec = error_of(R"({"specular": "wpow"})");
  EXPECT_NE(spec.find("specular: expected an object"), std::string::npos) << spec;
  const std::string kind = error_of(R"({"specular": {"kind": "wpw"}})");
  EXPECT_NE(kind.find("specular.kind"), std::string::npos) << kind;
  EXPECT_NE(kind.find("wpow"), std::string::npos) << "should list the units: " << kind;
  const std::string format = error_of(R"({"series": "s4,28"})");
  EXPECT_NE(format.find("series"), std::string::npos) << format;
  EXPECT_NE(format.find("expected s<int>.<frac>"), std::string::npos) << format;
  const std::string range = error_of(R"({"lights": 9})");
  EXPECT_NE(range.find("lights: expected 1..8"), std::string::npos) << range;
  const std::string top = error_of(R"([1, 2])");
  EXPECT_NE(top.find("expected a JSON object"), std::string::npos) << top;
}

// start_depth: read from a file, written back only when it is not the default, out of range named.
TEST_F(UnitConfigFile, StartDepthIsReadWrittenAndRangeChecked) {
  const UnitConfig one =
      load_unit_config(write("d1.json", R"({"span_setup": "host", "start_depth": 1})"), {});
  EXPECT_EQ(one.start_depth, 1);
  EXPECT_NE(one.to_string().find("start_depth=1"), std::string::npos) << one.to_string();
  const std::string text = config_to_json(one);
  EXPECT_NE(text.find("\"start_depth\":1"), std::string::npos) << text;
  EXPECT_EQ(load_unit_config(write("again.json", text), {}).start_depth, 1);
  const UnitConfig two = load_unit_config(write("host.json", R"({"span_setup": "host"})"), {});
  EXPECT_EQ(two.start_depth, 2);
  EXPECT_EQ(config_to_json(two).find("start_depth"), std::string::npos) << config_to_json(two);
  const std::string range = error_of(R"({"span_setup": "host", "start_depth": 3})");
  EXPECT_NE(range.find("start_depth: expected 1..2"), std::string::npos) << range;
}

// combine_stages: read, written back only when pipelined, out of range named.
TEST_F(UnitConfigFile, CombineStagesAreReadWrittenAndRangeChecked) {
  const UnitConfig piped = load_unit_config(write("c1.json", R"({"combine_stages": 1})"), {});
  EXPECT_EQ(piped.combine_stages, 1);
  EXPECT_NE(piped.to_string().find("combine_stages=1"), std::string::npos) << piped.to_string();
  const std::string text = config_to_json(piped);
  EXPECT_NE(text.find("\"combine_stages\":1"), std::string::npos) << text;
  EXPECT_EQ(load_unit_config(write("again.json", text), {}).combine_stages, 1);
  EXPECT_EQ(config_to_json(UnitConfig{}).find("combine_stages"), std::string::npos);
  EXPECT_EQ(load_unit_config(write("c2.json", R"({"combine_stages": 2})"), {}).combine_stages, 2);
  const std::string range = error_of(R"({"combine_stages": 3})");
  EXPECT_NE(range.find("combine_stages: expected 0..2"), std::string::npos) << range;
}

TEST_F(UnitConfigFile, ContradictoryFieldsAreRejectedByValidate) {
  // A wrapping coef format with fewer integer bits than the series loses the value.
  const std::string wrap = error_of(R"({"coef": "s3.32:rnd:wrap", "series": "s4.28:wrap"})");
  EXPECT_NE(wrap.find("coef"), std::string::npos) << wrap;
  const std::string ch = error_of(R"({"channels": 2})");
  EXPECT_NE(ch.find("channels must be 1 or 3"), std::string::npos) << ch;
}

TEST_F(UnitConfigFile, SyntaxErrorNamesLineAndColumn) {
  // '@' is the 13th character of line 3.
  const std::string msg =
      error_of("{\n  \"channels\": 3,\n  \"lights\": @,\n  \"xy_bits\": 11\n}\n");
  EXPECT_NE(msg.find("bad.json:3:13:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("JSON syntax error"), std::string::npos) << msg;
  // A missing closing brace: the error is at the end of the input, line 2.
  const std::string eof = error_of("{\n  \"channels\": 3\n");
  EXPECT_NE(eof.find("bad.json:3:"), std::string::npos) << eof;
}

TEST_F(UnitConfigFile, MissingFileIsAnError) {
  const std::string path = (dir_ / "absent.json").string();
  try {
    (void)load_unit_config(path);
    FAIL() << "expected an error";
  } catch (const UnitConfigFileError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": cannot open"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace shadesim
