// Writes the seed corpus of fuzz_mesh_answer: the import process's real answer for every file of
// a model folder up to 32 KiB (assimp-testmodels, its malformed files included), one seed file
// each, up to 64 KiB of answer. Files on which assimp crashes or runs away have no answer and are
// passed over. Usage: mesh_answer_seeds MODELS_DIR OUT_DIR
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "host/mesh_import.h"

namespace fs = std::filesystem;

// libFuzzer's longest input defaults to the longest seed: a tessellated NFF's megabytes of
// vertices would make every mutation that long.
constexpr size_t kMaxSeedBytes = size_t{64} * 1024;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: mesh_answer_seeds MODELS_DIR OUT_DIR\n");
    return 2;
  }
  const fs::path models = argv[1];
  const fs::path out = argv[2];
  std::error_code error;
  if (!fs::is_directory(models, error)) {
    std::fprintf(stderr, "mesh_answer_seeds: %s is not a folder (expected assimp-testmodels)\n",
                 models.c_str());
    return 1;
  }
  fs::create_directories(out);
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(models)) {
    if (entry.is_regular_file() && entry.file_size() <= std::uintmax_t{32} * 1024)
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  shadesim::MeshImporter importer(10);  // the fuzz harnesses' CPU limit per file
  int written = 0;
  for (const fs::path& file : files) {
    std::string answer;
    try {
      answer = importer.import_answer(file.string());
    } catch (const shadesim::SceneError&) {
      continue;  // assimp crashed or ran away: no answer to keep
    }
    if (answer.size() > kMaxSeedBytes) continue;
    char prefix[16];
    std::snprintf(prefix, sizeof prefix, "%04d_", ++written);
    std::ofstream seed(out / (prefix + file.filename().string() + ".answer"), std::ios::binary);
    seed.write(answer.data(), static_cast<std::streamsize>(answer.size()));
    if (!seed) {
      std::fprintf(stderr, "mesh_answer_seeds: cannot write into %s\n", out.c_str());
      return 1;
    }
  }
  std::printf("mesh_answer_seeds: %d seeds in %s\n", written, out.c_str());
  return written > 0 ? 0 : 1;
}
