// The derivation cache (sim/engines/derivation_cache.h): a second derivation of the same content is
// read back, and what it gives equals a fresh derive_config; any change to what the derivation
// reads (a scene byte, a mesh byte, an option) misses; an entry that cannot be used is named in a
// warning and replaced by a fresh derivation; and the commands say on their unit line that the
// own unit was reused. Every expected unit comes from derive_config run here, never from the
// cache or a copied constant. Scenes and caches live in a temporary folder per test.
#include "sim/engines/derivation_cache.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "derive/derive_config.h"
#include "model/command_stream.h"
#include "model/text_file.h"
#include "model/unit_config_file.h"
#include "sim/engines/derivation_key.h"
#include "tests/support/cli_run.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

const fs::path kScenes = fs::path(SHADESIM_SOURCE_DIR) / "scenes";

// The project's reader and writer: a missing file fails the test naming it, not as "".
std::string read_all(const fs::path& p) { return read_text_file(p.string()); }
void write_all(const fs::path& p, const std::string& text) { write_text_file(p.string(), text); }

// Everything config prints of a derivation, as one comparable text.
std::string printed(const DerivedConfig& d) {
  std::string s = config_to_json(d.config) + '\n';
  for (const FieldReason& r : d.reasons) s += r.field + " = " + r.value + ": " + r.reason + '\n';
  for (const std::string& m : d.cycles_misses) s += m + '\n';
  const ConfigMeasurements& m = d.measured;
  for (double v : {m.budget_lsb, m.max_monomial_sum, m.series_min, m.series_max, m.coef_max, m.gain,
                   m.drift_share_lsb, m.colour_max, m.product_max})
    s += std::to_string(v) + ' ';
  return s + std::to_string(m.longest_span) + (d.substitute ? " substitute" : "");
}

class DerivationCache : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("shadesim_derivation_cache_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    cache_ = (dir_ / "cache").string();
    // sphere (fast), and long_span with the mesh file it names by a relative path.
    sphere_ = (dir_ / "sphere.json").string();
    fs::copy_file(kScenes / "sphere.json", sphere_);
    fs::create_directories(dir_ / "mesh");
    mesh_scene_ = (dir_ / "mesh" / "long_span.json").string();
    mesh_ = (dir_ / "mesh" / "long_span_tri.obj").string();
    fs::copy_file(kScenes / "hard" / "long_span.json", mesh_scene_);
    fs::copy_file(kScenes / "hard" / "long_span_tri.obj", mesh_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  CachedDerivation cached(const std::string& scene, const DeriveOptions& o = {}) {
    warnings_.str("");
    return cached_derive_config({scene}, o, cache_, warnings_);
  }

  fs::path dir_;
  std::string cache_, sphere_, mesh_scene_, mesh_;
  std::ostringstream warnings_;
};

TEST_F(DerivationCache, TheSecondCallReadsTheEntryAndEqualsAFreshDerivation) {
  for (const std::string& scene : {sphere_, mesh_scene_}) {
    const CachedDerivation first = cached(scene);
    EXPECT_FALSE(first.reused);
    ASSERT_TRUE(fs::exists(first.entry)) << first.entry;
    EXPECT_EQ(fs::path(first.entry).parent_path(), fs::path(cache_));
    EXPECT_NE(first.origin().find("derived, cached as " + first.entry), std::string::npos);
    const CachedDerivation second = cached(scene);
    EXPECT_TRUE(second.reused);
    EXPECT_EQ(second.entry, first.entry);
    EXPECT_EQ(second.origin(), "cached derivation, " + first.entry);
    EXPECT_EQ(warnings_.str(), "");
    const DerivedConfig fresh = derive_config({scene}, DeriveOptions{});
    EXPECT_EQ(config_to_json(second.derived.config), config_to_json(fresh.config)) << scene;
    EXPECT_EQ(printed(second.derived), printed(fresh)) << scene;
  }
}

TEST_F(DerivationCache, TheEntryIsAUnitConfigFileWithItsKeyInside) {
  const CachedDerivation d = cached(mesh_scene_);
  const DerivationKey key = derivation_key({mesh_scene_}, DeriveOptions{});
  EXPECT_EQ(fs::path(d.entry).filename().string(), key.hex + ".json");
  const nlohmann::json j = nlohmann::json::parse(read_all(d.entry));
  EXPECT_EQ(j["derivation"]["cache"]["key"], key.hex);
  // The mesh, resolved from the scene's folder as load_scene resolves it.
  EXPECT_EQ(j["derivation"]["cache"]["inputs"]["scenes"][0]["meshes"][0]["file"],
            (dir_ / "mesh" / "long_span_tri.obj").string());
  // load_unit_config (--config FILE) reads the entry as the unit.
  EXPECT_EQ(config_to_json(load_unit_config(d.entry)), config_to_json(d.derived.config));
}

TEST_F(DerivationCache, AChangedMeshByteIsAMiss) {
  const CachedDerivation before = cached(mesh_scene_);
  // One byte of the mesh file (its comment: the geometry, and so the unit, may stay the same;
  // the key must not).
  std::string obj = read_all(mesh_);
  obj[obj.find("One triangle")] = 'o';
  write_all(mesh_, obj);
  const CachedDerivation after = cached(mesh_scene_);
  EXPECT_FALSE(after.reused);
  EXPECT_NE(after.entry, before.entry);
  EXPECT_EQ(config_to_json(after.derived.config),
            config_to_json(derive_config({mesh_scene_}, DeriveOptions{}).config));
  EXPECT_TRUE(cached(mesh_scene_).reused);
}

TEST_F(DerivationCache, AChangedSceneByteIsAMiss) {
  const CachedDerivation before = cached(sphere_);
  // Another light direction: a byte of the scene that changes what is shaded.
  std::string text = read_all(sphere_);
  const size_t at = text.find("\"direction\"");
  ASSERT_NE(at, std::string::npos);
  const size_t digit = text.find_first_of("123456789", at);
  text[digit] = text[digit] == '9' ? '8' : static_cast<char>(text[digit] + 1);
  write_all(sphere_, text);
  const CachedDerivation after = cached(sphere_);
  EXPECT_FALSE(after.reused);
  EXPECT_NE(after.entry, before.entry);
  EXPECT_EQ(printed(after.derived), printed(derive_config({sphere_}, DeriveOptions{})));
}

TEST_F(DerivationCache, OtherDeriveOptionsAreAMiss) {
  const CachedDerivation plain = cached(sphere_);
  DeriveOptions o;
  o.budget_lsb = 3;
  const CachedDerivation wider = cached(sphere_, o);
  EXPECT_FALSE(wider.reused);
  EXPECT_NE(wider.entry, plain.entry);
  EXPECT_EQ(printed(wider.derived), printed(derive_config({sphere_}, o)));
  EXPECT_TRUE(cached(sphere_, o).reused);
  EXPECT_TRUE(cached(sphere_).reused);
}

TEST_F(DerivationCache, EveryDeriveOptionIsInTheKey) {
  const std::string base = derive_options_json(DeriveOptions{}).dump();
  const std::vector<std::pair<const char*, std::function<void(DeriveOptions&)>>> changes = {
      {"budget_lsb", [](DeriveOptions& o) { o.budget_lsb = 1.0; }},
      {"out_bits", [](DeriveOptions& o) { o.out_bits = 10; }},
      {"ideal_substitute", [](DeriveOptions& o) { o.ideal_substitute.wpow.base_bits = 12; }},
      {"ideal_fallbacks", [](DeriveOptions& o) { o.ideal_fallbacks.pop_back(); }},
      {"search_named_units", [](DeriveOptions& o) { o.search_named_units = false; }},
      {"specular_trial", [](DeriveOptions& o) { o.specular_trial = SpecularConfig{}; }},
      {"max_depth", [](DeriveOptions& o) { o.max_depth = 11; }},
      {"hold_gate", [](DeriveOptions& o) { o.hold_gate = false; }},
      {"port_words", [](DeriveOptions& o) { o.port_words = 1; }},
      {"tri_queue", [](DeriveOptions& o) { o.tri_queue = 1; }},
      {"span_setup", [](DeriveOptions& o) { o.span_setup = SpanSetupSite::kUnit; }},
      {"diffuse_colour", [](DeriveOptions& o) { o.diffuse_colour = DiffuseColour::kSeries; }},
      {"lanes", [](DeriveOptions& o) { o.lanes = 4; }},
      {"max_cycles_per_pixel", [](DeriveOptions& o) { o.max_cycles_per_pixel = 1.2; }},
      // Given as the default's figure, it is still a request: a target per pixel, not per beat.
      {"max_cycles_per_pixel given", [](DeriveOptions& o) { o.max_cycles_per_pixel = 1.10; }}};
  std::set<std::string> seen = {base};
  for (const auto& [field, change] : changes) {
    DeriveOptions o;
    change(o);
    EXPECT_TRUE(seen.insert(derive_options_json(o).dump()).second) << field;
  }
}

TEST_F(DerivationCache, AnUnusableEntryIsNamedInAWarningAndDerivedAgain) {
  const CachedDerivation good = cached(sphere_);
  const std::string entry = good.entry, whole = read_all(entry);
  const std::string fresh = printed(derive_config({sphere_}, DeriveOptions{}));
  // Another scene's entry: valid JSON and a valid unit, with a foreign key inside.
  const std::string foreign = read_all(cached(mesh_scene_).entry);
  nlohmann::json invalid = nlohmann::json::parse(whole);
  invalid["channels"] = 2;  // UnitConfig::validate: 1 or 3
  nlohmann::json edited = nlohmann::json::parse(whole);
  edited["xy_bits"] = 12;  // a valid unit, not the one the entry's hash stands for
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"garbage bytes", std::string("\x00\xff\x13garbage", 10)},
      {"truncated JSON", whole.substr(0, whole.size() / 2)},
      {"empty file", ""},
      {"a foreign key", foreign},
      {"a unit that fails validate()", invalid.dump(2)},
      {"an edited unit", edited.dump(2)},
      {"JSON that is no object", "[1, 2, 3]"}};
  for (const auto& [what, text] : bad) {
    write_all(entry, text);
    const CachedDerivation d = cached(sphere_);
    EXPECT_FALSE(d.reused) << what;
    EXPECT_NE(warnings_.str().find("warning: unit cache entry " + entry + " is unusable"),
              std::string::npos)
        << what << ": " << warnings_.str();
    EXPECT_EQ(printed(d.derived), fresh) << what;
    // Overwritten with the fresh derivation: the next call reads it, silently.
    EXPECT_TRUE(cached(sphere_).reused) << what;
    EXPECT_EQ(warnings_.str(), "") << what;
  }
}

TEST_F(DerivationCache, NoFolderMeansNoCache) {
  warnings_.str("");
  const CachedDerivation d = cached_derive_config({sphere_}, DeriveOptions{}, "", warnings_);
  EXPECT_FALSE(d.reused);
  EXPECT_EQ(d.entry, "");
  EXPECT_EQ(d.origin(), "derived");
  EXPECT_FALSE(fs::exists(cache_));
}

// The commands, as a user runs them, with the cache in a folder of the test's own
// (SHADESIM_UNIT_CACHE): config writes the entry, and render, cycles and config again say on
// their unit line that they reused it, with the unit a fresh derivation gives.
TEST_F(DerivationCache, CommandsSayOnTheirUnitLineThatTheOwnUnitWasReused) {
  const std::string env = "SHADESIM_UNIT_CACHE=" + cache_ + " ";
  const std::string shadesim = std::string(SHADESIM_BINARY_DIR) + "/shadesim ";
  const Result config = run_shell(env + shadesim + "config " + sphere_ + " --clock-mhz 0");
  ASSERT_EQ(config.status, 0) << config.output;
  std::smatch m;
  const std::regex written("unit +(.*)  \\(derived, cached as (" + cache_ +
                           "/[0-9a-f]{32}\\.json)\\)");
  ASSERT_TRUE(std::regex_search(config.output, m, written)) << config.output;
  const std::string entry = m[2];
  const std::string unit = derive_config({sphere_}, DeriveOptions{}).config.to_string();
  EXPECT_EQ(m[1], unit);
  const std::string reused =
      "unit         " + unit + "  (--config own: cached derivation, " + entry + ")";
  const Result cycles = run_shell(env + shadesim + "cycles " + sphere_);
  ASSERT_EQ(cycles.status, 0) << cycles.output;
  EXPECT_NE(cycles.output.find(reused), std::string::npos) << cycles.output;
  const Result render =
      run_shell(env + shadesim + "render " + sphere_ + " --out " + (dir_ / "r").string());
  ASSERT_EQ(render.status, 0) << render.output;
  EXPECT_NE(render.output.find(reused), std::string::npos) << render.output;
  const Result again = run_shell(env + shadesim + "config " + sphere_ + " --clock-mhz 0");
  EXPECT_NE(again.output.find("unit         " + unit + "  (cached derivation, " + entry + ")"),
            std::string::npos)
      << again.output;
  // Off: derived, and said so.
  const Result off = run_shell("SHADESIM_UNIT_CACHE=off " + shadesim + "cycles " + sphere_);
  EXPECT_NE(off.output.find("unit         " + unit + "  (--config own: derived)"),
            std::string::npos)
      << off.output;
}

TEST_F(DerivationCache, RegressSaysItsOwnUnitWasReused) {
#ifndef SHADESIM_HAVE_RTL
  GTEST_SKIP() << "RTL not built (configure with -DSHADESIM_RTL=ON)";
#endif
  const std::string env = "SHADESIM_UNIT_CACHE=" + cache_ + " ";
  const std::string shadesim = std::string(SHADESIM_BINARY_DIR) + "/shadesim ";
  const Result config = run_shell(env + shadesim + "config " + sphere_ + " --clock-mhz 0");
  ASSERT_EQ(config.status, 0) << config.output;
  const Result r = run_shell(env + shadesim + "regress " + sphere_ + " --backends cpp --out " +
                             (dir_ / "reg").string());
  ASSERT_EQ(r.status, 0) << r.output;
  // The configurations table: "  own:sphere  <unit>  (cached derivation, <entry>)".
  const std::string unit = derive_config({sphere_}, DeriveOptions{}).config.to_string();
  std::istringstream lines(r.output);
  std::string own;
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("  own:sphere ", 0) == 0) own = line;
  EXPECT_NE(own.find(unit + "  (cached derivation, " + cache_ + "/"), std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace shadesim
