// The inputs the fuzzers of tests/fuzz/ found crashing (tests/fuzz/regressions/), run through
// the product's readers in the normal build: each must end in the reader's documented error,
// with a message that names the file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "host/mesh.h"
#include "host/scene.h"
#include "model/unit_config_file.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

const fs::path kRegressions = fs::path(SHADESIM_SOURCE_DIR) / "tests/fuzz/regressions";

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<fs::path> inputs_of(const std::string& harness) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(kRegressions / harness))
    files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

// fuzz_mesh's input form: "<extension>\n<file bytes>".
fs::path mesh_file_of(const fs::path& input, const fs::path& dir) {
  const std::string bytes = read_bytes(input);
  const size_t newline = bytes.find('\n');
  EXPECT_NE(newline, std::string::npos) << input;
  const fs::path file = dir / ("mesh." + bytes.substr(0, newline));
  std::ofstream(file, std::ios::binary) << bytes.substr(newline + 1);
  return file;
}

std::string load_error(const fs::path& file) {
  try {
    load_mesh_file(file.string());
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(FuzzRegressions, EveryMeshInputIsASceneErrorNamingTheFile) {
  const fs::path dir =
      fs::temp_directory_path() / ("shadesim-fuzz-regress-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::vector<fs::path> inputs = inputs_of("mesh");
  ASSERT_GE(inputs.size(), 2u);
  for (const fs::path& input : inputs) {
    const fs::path file = mesh_file_of(input, dir);
    const std::string message = load_error(file);
    EXPECT_NE(message.find(file.string()), std::string::npos)
        << input << ": expected a SceneError naming " << file << ", got '" << message << "'";
  }
  fs::remove_all(dir);
}

// The RAW file of assimp-testmodels that kills Debian's assimp in post-processing: the crash is
// the import child's, and the message says so.
TEST(FuzzRegressions, AssimpCrashIsReportedNotFatal) {
  const fs::path dir =
      fs::temp_directory_path() / ("shadesim-fuzz-crash-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = mesh_file_of(kRegressions / "mesh/assimp_raw_postprocess_segv.raw.in", dir);
  const std::string message = load_error(file);
  EXPECT_NE(message.find("assimp crashed"), std::string::npos) << message;
  fs::remove_all(dir);
}

// A scene that names the crashing mesh reports it at the object's "file" field.
TEST(FuzzRegressions, SceneWithCrashingMeshNamesTheField) {
  const fs::path dir =
      fs::temp_directory_path() / ("shadesim-fuzz-scene-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path mesh = mesh_file_of(kRegressions / "mesh/assimp_raw_postprocess_segv.raw.in", dir);
  const fs::path scene = dir / "scene.json";
  std::ofstream(scene) << R"({"image": {"width": 8, "height": 8}, "camera": {},
    "lights": [{"direction": [0, 0, 1]}], "materials": [{"name": "m"}],
    "objects": [{"type": "mesh", "material": "m", "file": ")"
                       << mesh.filename().string() << R"("}]})";
  try {
    load_scene(scene.string());
    ADD_FAILURE() << "expected a SceneError";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("objects[0].file"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

// Every UnitConfig input is a UnitConfigFileError naming the file, and for a JSON error its line
// and column (the fuzzer's crash was an nlohmann exception that escaped the reader).
TEST(FuzzRegressions, EveryUnitConfigInputIsAUnitConfigFileErrorNamingTheFile) {
  const std::vector<fs::path> inputs = inputs_of("unit_config");
  ASSERT_GE(inputs.size(), 1u);
  for (const fs::path& input : inputs) {
    std::string message;
    try {
      load_unit_config(input.string());
    } catch (const UnitConfigFileError& e) {
      message = e.what();
    }
    EXPECT_EQ(message.rfind(input.string() + ":", 0), 0u) << input << ": got '" << message << "'";
  }
  const fs::path overflow = kRegressions / "unit_config/number_beyond_double_range.json";
  std::string message;
  try {
    load_unit_config(overflow.string());
  } catch (const UnitConfigFileError& e) {
    message = e.what();
  }
  // 8e8888 starts at line 1, column 28 of the file.
  EXPECT_EQ(message.rfind(overflow.string() + ":1:28: JSON syntax error: number overflow", 0), 0u)
      << message;
  EXPECT_NE(message.find("expected a number within double range"), std::string::npos) << message;
}

}  // namespace
}  // namespace shadesim
