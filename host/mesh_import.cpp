#include "host/mesh_import.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace shadesim {
namespace {

bool is_finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Assimp's loaders trust element counts in file headers: the OFF loader, given
// assimp-testmodels' invalid/OutOfMemory.off (1.3e9 vertices declared, 8 present), allocates and
// fills ~24 GB and the process dies to the OOM killer instead of failing cleanly. While importing,
// cap the address space a few GiB above current use so such a file ends in std::bad_alloc, which
// assimp's Importer catches and reports. Set in the import process, per import.
class AddressSpaceCap {
 public:
  explicit AddressSpaceCap(rlim_t extra_bytes) {
    if (getrlimit(RLIMIT_AS, &saved_) != 0) return;
    const rlim_t in_use = current_virtual_size();
    if (in_use == 0) return;
    rlimit capped = saved_;
    const rlim_t wanted = in_use + extra_bytes;
    if (capped.rlim_cur == RLIM_INFINITY || capped.rlim_cur > wanted) capped.rlim_cur = wanted;
    active_ = setrlimit(RLIMIT_AS, &capped) == 0;
  }
  ~AddressSpaceCap() {
    if (active_) setrlimit(RLIMIT_AS, &saved_);
  }
  AddressSpaceCap(const AddressSpaceCap&) = delete;
  AddressSpaceCap& operator=(const AddressSpaceCap&) = delete;

 private:
  static rlim_t current_virtual_size() {
    std::FILE* statm = std::fopen("/proc/self/statm", "r");
    if (statm == nullptr) return 0;
    unsigned long pages = 0;
    const int read = std::fscanf(statm, "%lu", &pages);
    std::fclose(statm);
    return read == 1 ? static_cast<rlim_t>(pages) * static_cast<rlim_t>(sysconf(_SC_PAGESIZE)) : 0;
  }
  rlimit saved_{};
  bool active_ = false;
};

constexpr rlim_t kImportAddressSpace = rlim_t{4} << 30;

// One mesh of an assimp scene as the import process sends it: positions and normals as x, y, z
// floats per vertex (no normals at all where the file has none: the parent generates them), and
// the vertex indices of its three-index faces (points and lines have nothing to shade),
// unchecked: the parent checks them (mesh_from_parts).
struct RawPart {
  std::vector<float> positions;
  std::vector<float> normals;
  std::vector<uint32_t> triangle_indices;
};

// Runs in the import process: only assimp and copying, so that everything that checks the data
// runs in the parent process, where the fuzzer's sanitizers and coverage see it.
std::vector<RawPart> import_with_assimp(const std::string& path) {
  Assimp::Importer importer;
  // No aiProcess_GenSmoothNormals: Debian's assimp 5.2 stores each face's normal at its vertex
  // indices before smoothing over the vertices at one position, so on a mesh whose loader shares
  // vertices between faces (OFF, PLY) every vertex gets the normal of the last face naming it
  // (Cube.off: +-x only, opposite across each face, so the shading normal field passes through
  // zero). mesh_from_parts generates the smooth normals instead.
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_PreTransformVertices);
  if (scene == nullptr) {
    throw SceneError(path + ": assimp could not read the mesh file: " + importer.GetErrorString());
  }
  std::vector<RawPart> parts;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* part = scene->mMeshes[m];
    RawPart raw;
    if (part != nullptr && part->HasPositions()) {
      for (unsigned v = 0; v < part->mNumVertices; ++v) {
        const aiVector3D& p = part->mVertices[v];
        raw.positions.insert(raw.positions.end(), {p.x, p.y, p.z});
        if (part->HasNormals()) {
          const aiVector3D& n = part->mNormals[v];
          raw.normals.insert(raw.normals.end(), {n.x, n.y, n.z});
        }
      }
      for (unsigned f = 0; f < part->mNumFaces; ++f) {
        const aiFace& face = part->mFaces[f];
        if (face.mNumIndices != 3) continue;
        raw.triangle_indices.insert(raw.triangle_indices.end(),
                                    {face.mIndices[0], face.mIndices[1], face.mIndices[2]});
      }
    }
    parts.push_back(std::move(raw));  // empty for a part without positions
  }
  return parts;
}

// The shadesim mesh of the imported parts, all merged; throws SceneError naming the file.
Mesh mesh_from_parts(const std::string& path, const std::vector<RawPart>& parts) {
  Mesh mesh;
  std::vector<bool> generate;  // per vertex: its part has no normals
  for (size_t m = 0; m < parts.size(); ++m) {
    const RawPart& part = parts[m];
    const size_t vertices = part.positions.size() / 3;
    const bool has_normals = !part.normals.empty();
    if (part.positions.size() % 3 != 0 ||
        (has_normals && part.normals.size() != part.positions.size()) ||
        part.triangle_indices.size() % 3 != 0) {
      throw SceneError(path + ": mesh " + std::to_string(m) + ": import sent inconsistent arrays");
    }
    const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    for (size_t v = 0; v < vertices; ++v) {
      const Vec3 position{part.positions[3 * v], part.positions[3 * v + 1],
                          part.positions[3 * v + 2]};
      if (!is_finite(position)) {
        throw SceneError(path + ": mesh " + std::to_string(m) + " vertex " + std::to_string(v) +
                         ": expected finite coordinates");
      }
      mesh.positions.push_back(position);
      // checked below, after all faces are known; a part without normals gets them generated
      mesh.normals.push_back(
          has_normals ? Vec3{part.normals[3 * v], part.normals[3 * v + 1], part.normals[3 * v + 2]}
                      : Vec3{0, 0, 0});
      generate.push_back(!has_normals);
    }
    for (size_t f = 0; f < part.triangle_indices.size() / 3; ++f) {
      const uint32_t* index = &part.triangle_indices[3 * f];
      if (index[0] >= vertices || index[1] >= vertices || index[2] >= vertices) {
        throw SceneError(path + ": mesh " + std::to_string(m) + " triangle " + std::to_string(f) +
                         ": expected vertex indices below " + std::to_string(vertices));
      }
      mesh.triangles.push_back({base + index[0], base + index[1], base + index[2]});
    }
  }
  if (mesh.triangles.empty()) {
    throw SceneError(path + ": expected at least one triangle, the file has none");
  }
  // Smooth normals where the file has none (what aiProcess_GenSmoothNormals means to do): at each
  // vertex the normalised sum of the unit normals of the planes that meet at its position, over
  // every triangle with a corner there whichever vertex index that corner has (vertices at one
  // position stay apart where their other attributes differ). A plane counts once however many
  // triangles a polygon was cut into, so a cube's corner normal is its diagonal whatever the
  // triangulation, as assimp gives it for unshared vertices. Zero-area triangles add nothing.
  std::vector<Vec3> face_sum(mesh.positions.size());
  std::vector<uint32_t> by_position(mesh.positions.size());  // vertex indices sorted by position
  for (uint32_t i = 0; i < by_position.size(); ++i) by_position[i] = i;
  auto position_less = [&](uint32_t a, uint32_t b) {
    const Vec3 &p = mesh.positions[a], &q = mesh.positions[b];
    return std::tie(p.x, p.y, p.z) < std::tie(q.x, q.y, q.z);
  };
  std::sort(by_position.begin(), by_position.end(), position_less);
  std::vector<uint32_t> group(mesh.positions.size());  // first vertex index at the same position
  for (size_t k = 0; k < by_position.size(); ++k) {
    const bool same = k > 0 && !position_less(by_position[k - 1], by_position[k]);
    group[by_position[k]] = same ? group[by_position[k - 1]] : by_position[k];
  }
  struct Corner {
    uint32_t group;
    Vec3 unit_normal;
  };
  std::vector<Corner> corners;
  for (const auto& t : mesh.triangles) {
    const Vec3 area_normal = cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                                   mesh.positions[t[2]] - mesh.positions[t[0]]);
    for (uint32_t i : t) face_sum[i] += area_normal;
    const double area = length(area_normal);
    const bool generated = generate[t[0]] || generate[t[1]] || generate[t[2]];
    if (generated && area > 0 && std::isfinite(area)) {
      for (uint32_t i : t) corners.push_back({group[i], area_normal / area});
    }
  }
  std::sort(corners.begin(), corners.end(), [](const Corner& a, const Corner& b) {
    return std::tie(a.group, a.unit_normal.x, a.unit_normal.y, a.unit_normal.z) <
           std::tie(b.group, b.unit_normal.x, b.unit_normal.y, b.unit_normal.z);
  });
  constexpr double kSamePlane = 1e-6;  // float positions of a planar polygon: ~1e-7 apart
  std::vector<Vec3> smooth_sum(mesh.positions.size());
  for (size_t k = 0; k < corners.size(); ++k) {
    const Corner& c = corners[k];
    const bool repeat = k > 0 && corners[k - 1].group == c.group &&
                        length(corners[k - 1].unit_normal - c.unit_normal) < kSamePlane;
    if (!repeat) smooth_sum[c.group] += c.unit_normal;
  }
  for (size_t i = 0; i < mesh.normals.size(); ++i) {
    if (generate[i]) mesh.normals[i] = smooth_sum[group[i]];
  }
  // Normals can still be zero or NaN (in the file, or summed to zero over opposite faces); give
  // those the area-weighted normal of their faces so every used vertex carries a unit normal.
  for (size_t i = 0; i < mesh.normals.size(); ++i) {
    Vec3 n = mesh.normals[i];
    if (!is_finite(n) || length(n) < 1e-12) n = face_sum[i];
    if (!is_finite(n) || length(n) < 1e-300) n = {0, 0, 1};  // only degenerate faces use it
    mesh.normals[i] = normalize(n);
  }
  return mesh;
}

// The import process: Debian's assimp 5.2 dereferences null in its post-processing on some files
// (assimp-testmodels' own RAW models among them, found by tests/fuzz/fuzz_mesh.cpp) and may loop
// or allocate without bound on others. A crash, a runaway or an exhausted address space ends the
// import process, and MeshImporter::load reports it as a SceneError naming the file instead of
// dying. Per file the process receives the path and answers with the raw parts (or its
// SceneError's message), each message framed by its byte count, over a socket pair: a socket,
// not a pipe, so that writing to a process that died is an error instead of SIGPIPE.
constexpr uint64_t kMaxPathBytes = 1 << 16;

bool send_all(int fd, const void* data, size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::send(fd, p, size, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<size_t>(n);
  }
  return true;
}

bool receive_all(int fd, void* data, size_t size) {
  char* p = static_cast<char*>(data);
  while (size > 0) {
    const ssize_t n = ::recv(fd, p, size, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<size_t>(n);
  }
  return true;
}

bool send_message(int fd, const std::string& bytes) {
  const uint64_t size = bytes.size();
  return send_all(fd, &size, sizeof size) && send_all(fd, bytes.data(), bytes.size());
}

// False when the peer is gone or announces more than `limit` bytes.
bool receive_message(int fd, std::string& bytes, uint64_t limit) {
  uint64_t size = 0;
  if (!receive_all(fd, &size, sizeof size) || size > limit) return false;
  bytes.resize(size);
  return receive_all(fd, bytes.data(), bytes.size());
}

void append(std::string& out, const void* data, size_t size) {
  out.append(static_cast<const char*>(data), size);
}

template <typename T>
void append_array(std::string& out, const std::vector<T>& items) {
  static_assert(std::is_trivially_copyable_v<T>, "sent as raw bytes");
  const uint64_t count = items.size();
  append(out, &count, sizeof count);
  append(out, items.data(), items.size() * sizeof(T));
}

// RLIMIT_CPU counts the whole life of the process, so each import gets its budget from now.
void limit_cpu_from_now(rlim_t seconds) {
  rusage usage{};
  rlimit cpu{};
  if (getrusage(RUSAGE_SELF, &usage) != 0 || getrlimit(RLIMIT_CPU, &cpu) != 0) return;
  const rlim_t used = static_cast<rlim_t>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) + 1;
  cpu.rlim_cur = used + seconds;
  if (cpu.rlim_max != RLIM_INFINITY && cpu.rlim_cur > cpu.rlim_max) cpu.rlim_cur = cpu.rlim_max;
  setrlimit(RLIMIT_CPU, &cpu);
}

// 'M' and the parts, or 'E' and the message of the SceneError the parent is to throw.
std::string import_answer(const std::string& path) {
  const AddressSpaceCap cap(kImportAddressSpace);
  std::string answer;
  std::string message;
  try {
    const std::vector<RawPart> parts = import_with_assimp(path);
    answer = "M";
    const uint64_t count = parts.size();
    append(answer, &count, sizeof count);
    for (const RawPart& part : parts) {
      append_array(answer, part.positions);
      append_array(answer, part.normals);
      append_array(answer, part.triangle_indices);
    }
    return answer;
  } catch (const SceneError& e) {
    message = e.what();
  } catch (const std::bad_alloc&) {
    message = path + ": assimp ran out of memory reading the mesh file (more than " +
              std::to_string(kImportAddressSpace >> 30) + " GiB; a corrupt element count?)";
  } catch (const std::exception& e) {
    message = path + ": assimp failed reading the mesh file: " + e.what();
  }
  answer = "E";
  append_array(answer, std::vector<char>(message.begin(), message.end()));
  return answer;
}

[[noreturn]] void serve_imports(int fd, pid_t parent, rlim_t cpu_seconds_per_file) {
  // A runaway import must not outlive the process that asked for it (a fuzzer ended by its own
  // timeout, a user's Ctrl-C): the kernel kills this one when the parent dies.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) _exit(0);  // it died before the line above
  // Crashes must end this process only, with the default action the parent can see, not a
  // handler the parent installed (sanitizers, libFuzzer).
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGXCPU}) std::signal(sig, SIG_DFL);
  const rlimit no_core{0, 0};  // a crash here is reported, not dumped
  setrlimit(RLIMIT_CORE, &no_core);
  std::string path;
  while (receive_message(fd, path, kMaxPathBytes)) {
    limit_cpu_from_now(cpu_seconds_per_file);
    if (!send_message(fd, import_answer(path))) _exit(3);
  }
  _exit(0);  // the parent closed its end
}

// Reads an import answer; false when the bytes are short or inconsistent.
class AnswerReader {
 public:
  explicit AnswerReader(const std::string& bytes) : bytes_(bytes) {}
  bool read(void* out, size_t size) {
    if (size == 0) return true;  // an empty vector's data() may be null
    if (bytes_.size() - at_ < size) return false;
    std::memcpy(out, bytes_.data() + at_, size);
    at_ += size;
    return true;
  }
  template <typename T>
  bool read_array(std::vector<T>& items) {
    uint64_t count = 0;
    if (!read(&count, sizeof count) || count > (bytes_.size() - at_) / sizeof(T)) return false;
    items.resize(count);
    return read(items.data(), count * sizeof(T));
  }
  bool at_end() const { return at_ == bytes_.size(); }

 private:
  const std::string& bytes_;
  size_t at_ = 0;
};

}  // namespace

MeshImporter::MeshImporter(int cpu_seconds_per_file) : cpu_seconds_per_file_(cpu_seconds_per_file) {
  if (cpu_seconds_per_file < 1) {
    throw std::invalid_argument("mesh import CPU limit must be at least 1 s per file, got " +
                                std::to_string(cpu_seconds_per_file));
  }
}

MeshImporter::~MeshImporter() {
  if (process_ >= 0) stop();
}

void MeshImporter::start(const std::string& path) {
  int fds[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0) {
    throw SceneError(path +
                     ": cannot import the mesh file: socketpair failed: " + std::strerror(errno));
  }
  std::fflush(nullptr);  // nothing buffered is written twice by the child
  const pid_t parent = ::getpid();
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw SceneError(path + ": cannot import the mesh file: fork failed: " + std::strerror(errno));
  }
  if (child == 0) {
    ::close(fds[0]);
    serve_imports(fds[1], parent, static_cast<rlim_t>(cpu_seconds_per_file_));
  }
  ::close(fds[1]);
  socket_ = fds[0];
  process_ = child;
  imports_ = 0;
}

int MeshImporter::stop() {
  ::close(socket_);  // the process sees the end of its requests and exits
  socket_ = -1;
  int status = 0;
  while (::waitpid(process_, &status, 0) < 0 && errno == EINTR) {
  }
  process_ = -1;
  return status;
}

std::string MeshImporter::exchange(const std::string& path) {
  if (process_ >= 0 && imports_ >= kImportsPerProcess) stop();
  if (process_ >= 0 && !send_message(socket_, path)) stop();  // it died since the last file
  if (process_ < 0) {
    start(path);
    if (!send_message(socket_, path)) {
      stop();
      throw SceneError(path + ": cannot import the mesh file: the import process did not start");
    }
  }
  ++imports_;
  std::string answer;
  if (receive_message(socket_, answer, kImportAddressSpace)) return answer;
  const int status = stop();
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const std::string what = sig == SIGXCPU
                                 ? "ran past " + std::to_string(cpu_seconds_per_file_) + " s of CPU"
                                 : std::string("crashed (") + strsignal(sig) + ")";
    throw SceneError(path + ": assimp " + what +
                     " reading the mesh file (expected a well-formed mesh file; Debian's assimp "
                     "mishandles this one)");
  }
  throw SceneError(path + ": mesh import process failed (exit status " +
                   std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
}

std::string MeshImporter::import_answer(const std::string& path) {
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw SceneError(path + ": cannot open mesh file (expected a readable file)");
  }
  return exchange(path);
}

Mesh MeshImporter::load(const std::string& path) {
  return mesh_from_import_answer(path, import_answer(path));
}

Mesh mesh_from_import_answer(const std::string& path, const std::string& answer) {
  AnswerReader reader(answer);
  char kind = 0;
  bool ok = reader.read(&kind, 1);
  if (ok && kind == 'E') {
    std::vector<char> message;
    // what() is a C string: a message that is empty or holds a NUL would reach the user empty
    // or cut short, and no real message is either (assimp's and ours are C strings with the path)
    if (!reader.read_array(message) || message.empty() || !reader.at_end() ||
        std::find(message.begin(), message.end(), '\0') != message.end()) {
      throw SceneError(path + ": mesh import process sent a malformed error");
    }
    throw SceneError(std::string(message.begin(), message.end()));
  }
  uint64_t count = 0;
  ok = ok && kind == 'M' && reader.read(&count, sizeof count);
  std::vector<RawPart> parts;
  for (uint64_t m = 0; ok && m < count; ++m) {
    RawPart part;
    ok = reader.read_array(part.positions) && reader.read_array(part.normals) &&
         reader.read_array(part.triangle_indices);
    parts.push_back(std::move(part));
  }
  if (!ok || !reader.at_end()) {
    throw SceneError(path + ": mesh import process sent a malformed result");
  }
  return mesh_from_parts(path, parts);
}

Mesh load_mesh_file(const std::string& path) { return MeshImporter().load(path); }

}  // namespace shadesim
