// A scene prepared once (host/prepared_scene.h) against a fresh prepare_frame of the same scene on
// the same unit (tests/support/render_at.h): the same command words, stats, reference and error.
// And the derivation that shares prepared frames between candidates and threads: the same unit,
// reasons and cycles whatever the thread count, each figure equal to a fresh frame's.
#include "host/prepared_scene.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "derive/derive_config.h"
#include "host/gate_flips.h"
#include "host/scene_error.h"
#include "model/command_stream.h"
#include "model/host_setup.h"
#include "tests/support/render_at.h"

namespace shadesim {
namespace {

std::string scene(const std::string& name) {
  return std::string(SHADESIM_SOURCE_DIR) + "/scenes/" + name;
}

const std::vector<std::string> kScenes = {"sphere.json", "specular.json", "torus.json",
                                          "multi.json", "suzanne.json"};

std::string reasons_text(const DerivedConfig& d) {
  std::string s;
  for (const auto& r : d.reasons) s += r.field + " = " + r.value + "  " + r.reason + "\n";
  return s;
}

TEST(PreparedScene, EncodesEveryUnitAsAFreshFrameDoes) {
  for (const std::string& name : kScenes) {
    const std::string path = scene(name);
    const UnitConfig own = derive_config({path}, DeriveOptions{}).config;
    UnitConfig unit_setup = own;
    unit_setup.span_setup = SpanSetupSite::kUnit;
    unit_setup.tri_queue = 1;
    const PreparedScene prepared(path, PrepareKey{std::nullopt, 12, own.out_bits});
    for (const UnitConfig& unit : {own, unit_setup}) {
      const EncodedFrame got = prepared.encode(unit);
      const PreparedFrame fresh = frame_at(path, unit);
      EXPECT_EQ(got.stream.encode(), fresh.encoded.stream.encode()) << name;
      EXPECT_EQ(got.stats.words, fresh.encoded.stats.words) << name;
      EXPECT_EQ(got.stats.pixels, fresh.encoded.stats.pixels) << name;
      EXPECT_EQ(got.stats.triangles, fresh.encoded.stats.triangles) << name;
      // The word count the encoder states is the length of the words it encodes.
      EXPECT_EQ(got.stats.words, got.stream.encode().size()) << name;
      EXPECT_EQ(got.stream.word_count(), got.stream.encode().size()) << name;
    }
  }
}

TEST(HostSetup, ConvertingInPlaceGivesTheCopysWords) {
  for (const std::string& name : kScenes) {
    UnitConfig unit = derive_config({scene(name)}, DeriveOptions{}).config;
    unit.span_setup = SpanSetupSite::kUnit;
    unit.tri_queue = 1;
    const CommandStream unit_stream = frame_at(scene(name), unit).encoded.stream;
    CommandStream consumed = unit_stream;
    const CommandStream copied = with_host_setup(unit_stream);
    const CommandStream in_place = with_host_setup(std::move(consumed));
    EXPECT_EQ(in_place.encode(), copied.encode()) << name;
    EXPECT_EQ(config_to_json(in_place.config), config_to_json(copied.config)) << name;
  }
}

TEST(PreparedScene, ErrorAndCyclesEqualAFreshFrames) {
  for (const std::string& name : kScenes) {
    const std::string path = scene(name);
    const UnitConfig own = derive_config({path}, DeriveOptions{}).config;
    const PreparedScene prepared(path, PrepareKey{std::nullopt, 12, own.out_bits});
    const ErrorStats fresh = render_at(path, own);
    for (int pass = 0; pass < 2; ++pass) {  // the second answer comes from the memo
      const ErrorStats got = scene_error(prepared, own);
      EXPECT_EQ(got.max_code_lsb, fresh.max_code_lsb) << name;
      EXPECT_EQ(got.pixels, fresh.pixels) << name;
      EXPECT_EQ(got.pixels_over_1lsb, fresh.pixels_over_1lsb) << name;
      EXPECT_DOUBLE_EQ(got.mean_code_lsb, fresh.mean_code_lsb) << name;
      EXPECT_DOUBLE_EQ(got.max_real_lsb, fresh.max_real_lsb) << name;
    }
    const SceneCycles c = scene_cycles(prepared, own), f = cycles_at(path, own);
    EXPECT_EQ(c.cycles, f.cycles) << name;
    EXPECT_EQ(c.pixels, f.pixels) << name;
  }
}

TEST(PreparedScene, GateFlipsRecordTheErrorOfAFreshFrame) {
  // measure_gate_flips on a prepared scene leaves the unit's error measured for scene_error:
  // that figure must be a fresh frame's.
  const std::string path = scene("multi.json");
  const UnitConfig own = derive_config({path}, DeriveOptions{}).config;
  const PreparedScene prepared(path, PrepareKey{std::nullopt, 12, own.out_bits});
  (void)measure_gate_flips(prepared, own, 1);
  const ErrorStats got = scene_error(prepared, own), fresh = render_at(path, own);
  EXPECT_EQ(got.max_code_lsb, fresh.max_code_lsb);
  EXPECT_EQ(got.pixels_over_1lsb, fresh.pixels_over_1lsb);
  EXPECT_DOUBLE_EQ(got.mean_code_lsb, fresh.mean_code_lsb);
}

TEST(PreparedScene, ANameThatCannotBePreparedIsAnError) {
  EXPECT_THROW(PreparedScene(scene("no_such_scene.json"), PrepareKey{}), SceneError);
  const PreparedScene prepared(scene("sphere.json"), PrepareKey{std::nullopt, 12, 8});
  UnitConfig ten_bits;
  ten_bits.out_bits = 10;
  EXPECT_THROW(prepared.encode(ten_bits), std::invalid_argument);  // setup's LSBs are 8-bit
  EXPECT_THROW(prepared.reference(2), std::invalid_argument);
}

TEST(Derivation, TheUnitAndEveryReasonAreTheSameForAnyThreadCount) {
  // specular and multi search several specular units: the candidates run side by side.
  for (const std::string& name : {"specular.json", "multi.json", "suzanne.json"}) {
    DeriveOptions one, two, five;
    one.threads = 1;
    two.threads = 2;
    five.threads = 5;
    const DerivedConfig a = derive_config({scene(name)}, one);
    const DerivedConfig b = derive_config({scene(name)}, two);
    const DerivedConfig c = derive_config({scene(name)}, five);
    EXPECT_EQ(config_to_json(a.config), config_to_json(b.config)) << name;
    EXPECT_EQ(config_to_json(a.config), config_to_json(c.config)) << name;
    EXPECT_EQ(reasons_text(a), reasons_text(b)) << name;
    EXPECT_EQ(reasons_text(a), reasons_text(c)) << name;
  }
}

TEST(Derivation, ItsCyclesAreTheUnitsOwnOnAFreshFrame) {
  for (const std::string& name : kScenes) {
    const DerivedConfig d = derive_config({scene(name)}, DeriveOptions{});
    ASSERT_EQ(d.cycles.size(), 1u) << name;
    const SceneCycles fresh = cycles_at(scene(name), d.config);
    EXPECT_EQ(d.cycles[0].cycles, fresh.cycles) << name;
    EXPECT_EQ(d.cycles[0].pixels, fresh.pixels) << name;
  }
}

TEST(Derivation, EveryCandidateSharesOnePreparedFramePerScene) {
  PreparedScenes store;
  const std::vector<std::string> paths = {scene("specular.json"), scene("sphere.json")};
  const DerivedConfig d = derive_config(FrameSet(store, paths, prepare_key({})), DeriveOptions{});
  EXPECT_EQ(store.prepared(), paths.size());
  EXPECT_EQ(config_to_json(d.config), config_to_json(derive_config(paths, {}).config));
}

}  // namespace
}  // namespace shadesim
