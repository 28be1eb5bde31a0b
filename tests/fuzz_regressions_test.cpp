// The inputs the fuzzers of tests/fuzz/ found crashing (tests/fuzz/regressions/), run through
// the product's readers in the normal build: each must end in the reader's documented error,
// with a message that names the file.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "host/mesh.h"
#include "host/mesh_import.h"
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

// A folder of this test process, removed when the test ends, an early return included.
struct ScratchDir {
  explicit ScratchDir(const std::string& name)
      : path(fs::temp_directory_path() /
             ("shadesim-fuzz-" + name + "-" + std::to_string(::getpid()))) {
    fs::create_directories(path);
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const fs::path path;
};

// fuzz_mesh's input form: "<extension>\n<file bytes>".
fs::path mesh_file_of(const fs::path& input, const fs::path& dir) {
  const std::string bytes = read_bytes(input);
  const size_t newline = bytes.find('\n');
  EXPECT_NE(newline, std::string::npos) << input;
  fs::path file = dir / ("mesh." + bytes.substr(0, newline));  // returned: moved
  std::ofstream(file, std::ios::binary) << bytes.substr(newline + 1);
  return file;
}

// A runaway import (lws_runaway_import) ends at this CPU limit instead of the product's 120 s.
constexpr int kCpuSecondsPerFile = 3;

std::string load_error(const fs::path& file) {
  try {
    MeshImporter(kCpuSecondsPerFile).load(file.string());
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(FuzzRegressions, EveryMeshInputIsASceneErrorNamingTheFile) {
  const ScratchDir scratch("regress");
  const fs::path& dir = scratch.path;
  const std::vector<fs::path> inputs = inputs_of("mesh");
  ASSERT_GE(inputs.size(), 2u);
  for (const fs::path& input : inputs) {
    const fs::path file = mesh_file_of(input, dir);
    const std::string message = load_error(file);
    EXPECT_NE(message.find(file.string()), std::string::npos)
        << input << ": expected a SceneError naming " << file << ", got '" << message << "'";
  }
}

// The RAW file of assimp-testmodels that kills Debian's assimp in post-processing: the crash is
// the import child's, and the message says so.
TEST(FuzzRegressions, AssimpCrashIsReportedNotFatal) {
  const ScratchDir scratch("crash");
  const fs::path& dir = scratch.path;
  const fs::path file = mesh_file_of(kRegressions / "mesh/assimp_raw_postprocess_segv.raw.in", dir);
  const std::string message = load_error(file);
  EXPECT_NE(message.find("assimp crashed"), std::string::npos) << message;
}

// One MeshImporter keeps its import process across files (the fuzzer's path): a file that kills
// the process is reported, the next file gets a new process and loads, and every answer is the
// one a process of its own gives (load_mesh_file).
TEST(FuzzRegressions, OneImporterSurvivesAnImportProcessCrash) {
  const ScratchDir scratch("importer");
  const fs::path& dir = scratch.path;
  const fs::path crash =
      mesh_file_of(kRegressions / "mesh/assimp_raw_postprocess_segv.raw.in", dir);
  const fs::path huge = mesh_file_of(kRegressions / "mesh/off_huge_vertex_count.off.in", dir);
  const fs::path good = dir / "tet.obj";
  std::ofstream(good) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  const Mesh alone = load_mesh_file(good.string());
  MeshImporter importer(kCpuSecondsPerFile);
  auto error_of = [&](const fs::path& file) -> std::string {
    try {
      importer.load(file.string());
    } catch (const SceneError& e) {
      return e.what();
    }
    return "";
  };
  for (int round = 0; round < 3; ++round) {
    SCOPED_TRACE(round);
    const Mesh shared = importer.load(good.string());
    EXPECT_EQ(shared.positions, alone.positions);
    EXPECT_EQ(shared.normals, alone.normals);
    EXPECT_EQ(shared.triangles, alone.triangles);
    EXPECT_EQ(error_of(huge), load_error(huge));
    const std::string crashed = error_of(crash);
    EXPECT_NE(crashed.find("assimp crashed"), std::string::npos) << crashed;
    EXPECT_EQ(crashed, load_error(crash));
  }
}

// A truncated LightWave scene on which Debian's assimp runs for minutes (found by fuzz_mesh as a
// timeout): the import ends at the CPU limit, and the message says so.
TEST(FuzzRegressions, RunawayImportEndsAtTheCpuLimit) {
  const ScratchDir scratch("runaway");
  const fs::path& dir = scratch.path;
  const fs::path file = mesh_file_of(kRegressions / "mesh/lws_runaway_import.lws.in", dir);
  const std::string message = load_error(file);
  EXPECT_NE(message.find("assimp ran past 3 s of CPU"), std::string::npos) << message;
}

// The import process dies with the process that asked for it: a runaway import must not keep a
// core busy after the fuzzer (or a user's Ctrl-C) ended its parent.
TEST(FuzzRegressions, ImportProcessDiesWithItsParent) {
  const ScratchDir scratch("orphan");
  const fs::path& dir = scratch.path;
  const fs::path file = mesh_file_of(kRegressions / "mesh/lws_runaway_import.lws.in", dir);
  const pid_t parent = ::fork();
  ASSERT_GE(parent, 0);
  if (parent == 0) {
    try {
      MeshImporter(100).load(file.string());
    } catch (...) {
    }
    _exit(0);
  }
  // The parent's only child is its import process, once it has started.
  const std::string children =
      "/proc/" + std::to_string(parent) + "/task/" + std::to_string(parent) + "/children";
  pid_t importer = 0;
  for (int tries = 0; tries < 200 && importer == 0; ++tries) {
    ::usleep(20000);
    std::ifstream(children) >> importer;
  }
  ::kill(parent, SIGKILL);
  ::waitpid(parent, nullptr, 0);
  ASSERT_GT(importer, 0) << "no import process under " << parent;
  // Dead means gone, or a zombie waiting for a reaper that is not us.
  auto alive = [&] {
    std::ifstream stat("/proc/" + std::to_string(importer) + "/stat");
    std::string pid, name, state;
    return stat >> pid >> name >> state && state != "Z" && state != "X";
  };
  for (int tries = 0; tries < 250 && alive(); ++tries) ::usleep(20000);
  EXPECT_FALSE(alive()) << "import process " << importer << " outlived its parent";
  if (alive()) ::kill(importer, SIGKILL);
}

// A scene that names the crashing mesh reports it at the object's "file" field.
TEST(FuzzRegressions, SceneWithCrashingMeshNamesTheField) {
  const ScratchDir scratch("scene");
  const fs::path& dir = scratch.path;
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
}

// Import answers built byte by byte from the wire form (host/mesh_import.h): 'M', a part count,
// then per part three arrays, each an element count and the elements.
class AnswerBytes {
 public:
  explicit AnswerBytes(char kind) : bytes_(1, kind) {}
  AnswerBytes& count(uint64_t n) { return raw(&n, sizeof n); }
  AnswerBytes& floats(std::vector<float> values) {
    count(values.size());
    return raw(values.data(), values.size() * sizeof(float));
  }
  AnswerBytes& indices(std::vector<uint32_t> values) {
    count(values.size());
    return raw(values.data(), values.size() * sizeof(uint32_t));
  }
  AnswerBytes& text(const std::string& message) {
    count(message.size());
    return raw(message.data(), message.size());
  }
  AnswerBytes& raw(const void* data, size_t size) {
    bytes_.append(static_cast<const char*>(data), size);
    return *this;
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

std::string answer_error(const std::string& answer) {
  try {
    mesh_from_import_answer("model.obj", answer);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

// Every fuzz_mesh_answer input ends in a SceneError naming the mesh file the answer stands for.
TEST(FuzzRegressions, EveryMeshAnswerInputIsASceneErrorNamingTheFile) {
  const std::vector<fs::path> inputs = inputs_of("mesh_answer");
  ASSERT_GE(inputs.size(), 1u);
  for (const fs::path& input : inputs) {
    const std::string message = answer_error(read_bytes(input));
    EXPECT_EQ(message.rfind("model.obj: ", 0), 0u) << input << ": got '" << message << "'";
  }
}

TEST(MeshImportAnswer, OneTriangleWithAZeroNormalGetsItsFaceNormal) {
  const std::string answer = AnswerBytes('M')
                                 .count(1)
                                 .floats({0, 0, 0, 2, 0, 0, 0, 2, 0})
                                 .floats({0, 0, 0, 0, 0, 1, 0, 0, 3})
                                 .indices({0, 1, 2})
                                 .bytes();
  const Mesh mesh = mesh_from_import_answer("model.obj", answer);
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_EQ(mesh.positions[1], (Vec3{2, 0, 0}));
  // The triangle lies in z = 0, counter-clockwise seen from +z: every normal is +z, the zero one
  // from the face and the long one normalised.
  for (const Vec3& n : mesh.normals) EXPECT_EQ(n, (Vec3{0, 0, 1}));
}

TEST(MeshImportAnswer, EachBrokenAnswerNamesWhatWasExpected) {
  const auto part = [](std::vector<float> positions, std::vector<uint32_t> triangle) {
    const size_t normals = positions.size();
    return AnswerBytes('M')
        .count(1)
        .floats(std::move(positions))
        .floats(std::vector<float>(normals, 1.0f))
        .indices(std::move(triangle));
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(answer_error(part({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 3}).bytes()),
            "model.obj: mesh 0 triangle 0: expected vertex indices below 3");
  EXPECT_EQ(answer_error(part({0, 0, 0, 1, nan, 0, 0, 1, 0}, {0, 1, 2}).bytes()),
            "model.obj: mesh 0 vertex 1: expected finite coordinates");
  EXPECT_EQ(answer_error(part({0, 0, 0, 1, 0, 0, 0, 1, 0}, {}).bytes()),
            "model.obj: expected at least one triangle, the file has none");
  EXPECT_EQ(answer_error(part({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2}).raw("x", 1).bytes()),
            "model.obj: mesh import process sent a malformed result");
  EXPECT_EQ(answer_error(AnswerBytes('M').count(2).floats({}).floats({}).indices({}).bytes()),
            "model.obj: mesh import process sent a malformed result");
  EXPECT_EQ(answer_error(AnswerBytes('E').text("model.obj: assimp could not read it").bytes()),
            "model.obj: assimp could not read it");
  EXPECT_EQ(answer_error(AnswerBytes('E').text(std::string("\0cut", 4)).bytes()),
            "model.obj: mesh import process sent a malformed error");
  EXPECT_EQ(answer_error(AnswerBytes('E').text("").bytes()),
            "model.obj: mesh import process sent a malformed error");
  EXPECT_EQ(answer_error(""), "model.obj: mesh import process sent a malformed result");
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
