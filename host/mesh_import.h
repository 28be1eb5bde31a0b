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

 private:
  void start(const std::string& path);
  int stop();  // the process's wait status
  std::string exchange(const std::string& path);

  int cpu_seconds_per_file_;
  int socket_ = -1;
  pid_t process_ = -1;
  int imports_ = 0;
};

// One file, in a process of its own (MeshImporter::load).
Mesh load_mesh_file(const std::string& path);

}  // namespace shadesim
