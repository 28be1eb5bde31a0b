// Mesh files through assimp, imported in a separate process so that what Debian's assimp does
// with a malformed file (crash, runaway loop, unbounded allocation) ends that process only and
// reaches the caller as a SceneError naming the file.
#pragma once

#include <sys/types.h>

#include <string>

#include "host/scene.h"

namespace shadesim {

// Owns one import process, started by the first load and kept for the next ones, so a caller
// that loads many files (the mesh fuzzer) pays for one fork per kImportsPerProcess files instead
// of one per file. A process that crashed is replaced at the next load.
class MeshImporter {
 public:
  // A fresh process after this many imports bounds what assimp leaks.
  static constexpr int kImportsPerProcess = 1000;

  // CPU time one file may take before its import is called a runaway and ended.
  static constexpr int kDefaultCpuSecondsPerFile = 120;

  explicit MeshImporter(int cpu_seconds_per_file = kDefaultCpuSecondsPerFile);
  ~MeshImporter();  // ends the import process
  MeshImporter(const MeshImporter&) = delete;
  MeshImporter& operator=(const MeshImporter&) = delete;

  // Reads any format assimp reads (OBJ, PLY, STL, DAE, BLEND, ...), triangulated, node
  // transforms applied, all meshes merged; smooth normals generated where the file has none.
  // Throws SceneError naming the file and what was expected.
  Mesh load(const std::string& path);

  // The import process's answer for one file, as it sent it: what load() decodes with
  // mesh_from_import_answer. Real answers seed the fuzzer of that decoder (tests/fuzz/).
  std::string import_answer(const std::string& path);

 private:
  void start(const std::string& path);
  int stop();  // the process's wait status
  std::string exchange(const std::string& path);

  int cpu_seconds_per_file_;
  int socket_ = -1;
  pid_t process_ = -1;
  int imports_ = 0;
};

// The caller's half of an import: an import process's answer (an 'M' and the parts assimp gave,
// or an 'E' and the message of the error to throw) decoded and checked into a Mesh. Everything
// that checks what assimp made of a file runs here, in the caller's process, where sanitizers and
// the fuzzer see it. Throws SceneError naming `path` on an error answer, a malformed answer, or
// parts that are no mesh (non-finite positions, indices out of range, no triangle).
Mesh mesh_from_import_answer(const std::string& path, const std::string& answer);

// One file, in a process of its own (MeshImporter::load).
Mesh load_mesh_file(const std::string& path);

}  // namespace shadesim
