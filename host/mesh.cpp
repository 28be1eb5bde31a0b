#include "host/mesh.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <assimp/Importer.hpp>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <type_traits>
#include <utility>
#include <vector>

namespace shadesim {
namespace {

constexpr double kPi = 3.14159265358979323846;

uint32_t add_vertex(Mesh& mesh, const Vec3& position, const Vec3& normal) {
  mesh.positions.push_back(position);
  mesh.normals.push_back(normalize(normal));
  return static_cast<uint32_t>(mesh.positions.size() - 1);
}

// Quad a=(s,t) b=(s+1,t) c=(s+1,t+1) d=(s,t+1) of a grid whose cross(d/ds, d/dt) points outward.
void add_quad(Mesh& mesh, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  mesh.triangles.push_back({a, b, c});
  mesh.triangles.push_back({a, c, d});
}

void check_tessellation(int tessellation, int minimum, const char* shape) {
  if (tessellation < minimum || tessellation > kMaxTessellation) {
    throw std::invalid_argument(std::string(shape) + " tessellation must be in " +
                                std::to_string(minimum) + ".." + std::to_string(kMaxTessellation) +
                                ", got " + std::to_string(tessellation));
  }
}

struct Mat3 {
  double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  Vec3 operator*(const Vec3& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  Mat3 operator*(const Mat3& o) const {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        r.m[i][j] = m[i][0] * o.m[0][j] + m[i][1] * o.m[1][j] + m[i][2] * o.m[2][j];
    return r;
  }
};

Mat3 rotation_x(double rad) {
  Mat3 r;
  r.m[1][1] = std::cos(rad);
  r.m[1][2] = -std::sin(rad);
  r.m[2][1] = std::sin(rad);
  r.m[2][2] = std::cos(rad);
  return r;
}
Mat3 rotation_y(double rad) {
  Mat3 r;
  r.m[0][0] = std::cos(rad);
  r.m[0][2] = std::sin(rad);
  r.m[2][0] = -std::sin(rad);
  r.m[2][2] = std::cos(rad);
  return r;
}
Mat3 rotation_z(double rad) {
  Mat3 r;
  r.m[0][0] = std::cos(rad);
  r.m[0][1] = -std::sin(rad);
  r.m[1][0] = std::sin(rad);
  r.m[1][1] = std::cos(rad);
  return r;
}

bool is_finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Assimp's loaders trust element counts in file headers: the OFF loader, given
// assimp-testmodels' invalid/OutOfMemory.off (1.3e9 vertices declared, 8 present), allocates and
// fills ~24 GB and the process dies to the OOM killer instead of failing cleanly. While importing,
// cap the address space a few GiB above current use so such a file ends in std::bad_alloc, which
// assimp's Importer catches and reports. Set in the import's child process (load_mesh_file).
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

}  // namespace

Mesh make_sphere(double radius, int tessellation) {
  check_tessellation(tessellation, kMinTessellation, "sphere");
  const int bands = tessellation;
  const int segments = 2 * tessellation;
  Mesh mesh;
  const uint32_t north = add_vertex(mesh, {0, radius, 0}, {0, 1, 0});
  std::vector<uint32_t> ring_start(bands + 1, 0);
  for (int i = 1; i < bands; ++i) {
    const double theta = kPi * i / bands;
    ring_start[i] = static_cast<uint32_t>(mesh.positions.size());
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * kPi * j / segments;
      const Vec3 n{std::sin(theta) * std::cos(phi), std::cos(theta),
                   std::sin(theta) * std::sin(phi)};
      add_vertex(mesh, n * radius, n);
    }
  }
  const uint32_t south = add_vertex(mesh, {0, -radius, 0}, {0, -1, 0});
  // s runs along phi, t along theta: cross(d/dphi, d/dtheta) points outward.
  auto at = [&](int i, int j) -> uint32_t {
    if (i == 0) return north;
    if (i == bands) return south;
    return ring_start[i] + static_cast<uint32_t>(j % segments);
  };
  for (int i = 0; i < bands; ++i) {
    for (int j = 0; j < segments; ++j) {
      const uint32_t a = at(i, j), b = at(i, j + 1), c = at(i + 1, j + 1), d = at(i + 1, j);
      if (i != 0) mesh.triangles.push_back({a, b, c});
      if (i != bands - 1) mesh.triangles.push_back({a, c, d});
    }
  }
  return mesh;
}

Mesh make_torus(double major_radius, double minor_radius, int tessellation) {
  check_tessellation(tessellation, kMinTessellation, "torus");
  const int around = 2 * tessellation;  // phi, around the y axis
  const int tube = tessellation;        // theta, around the tube
  Mesh mesh;
  for (int j = 0; j < around; ++j) {
    const double phi = 2 * kPi * j / around;
    const Vec3 radial{std::cos(phi), 0, std::sin(phi)};
    for (int i = 0; i < tube; ++i) {
      const double theta = 2 * kPi * i / tube;
      const Vec3 n = radial * std::cos(theta) + Vec3{0, std::sin(theta), 0};
      add_vertex(mesh, radial * major_radius + n * minor_radius, n);
    }
  }
  // s runs along theta, t along phi: cross(d/dtheta, d/dphi) points outward.
  auto at = [&](int i, int j) { return static_cast<uint32_t>((j % around) * tube + (i % tube)); };
  for (int j = 0; j < around; ++j)
    for (int i = 0; i < tube; ++i)
      add_quad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
  return mesh;
}

Mesh make_cylinder(double radius, double height, int tessellation) {
  check_tessellation(tessellation, kMinTessellation, "cylinder");
  const int around = tessellation;
  const double half = height / 2;
  Mesh mesh;
  std::vector<Vec3> rim(around);
  for (int j = 0; j < around; ++j) {
    const double phi = 2 * kPi * j / around;
    rim[j] = {std::cos(phi), 0, std::sin(phi)};
  }
  // Side: rows y = -half (index j) and y = +half (index around + j).
  for (int row = 0; row < 2; ++row)
    for (int j = 0; j < around; ++j)
      add_vertex(mesh, rim[j] * radius + Vec3{0, row ? half : -half, 0}, rim[j]);
  // s runs along y, t along phi: cross(d/dy, d/dphi) points outward.
  for (int j = 0; j < around; ++j) {
    const uint32_t j0 = static_cast<uint32_t>(j), j1 = static_cast<uint32_t>((j + 1) % around);
    const uint32_t top = static_cast<uint32_t>(around);
    add_quad(mesh, j0, top + j0, top + j1, j1);
  }
  // Caps: fans about their centres, rim vertices duplicated with the flat cap normal.
  for (int cap = 0; cap < 2; ++cap) {
    const double y = cap ? half : -half;
    const Vec3 normal{0, cap ? 1.0 : -1.0, 0};
    const uint32_t centre = add_vertex(mesh, {0, y, 0}, normal);
    const uint32_t first = static_cast<uint32_t>(mesh.positions.size());
    for (int j = 0; j < around; ++j) add_vertex(mesh, rim[j] * radius + Vec3{0, y, 0}, normal);
    for (int j = 0; j < around; ++j) {
      const uint32_t a = first + static_cast<uint32_t>(j);
      const uint32_t b = first + static_cast<uint32_t>((j + 1) % around);
      // Increasing phi runs clockwise seen from +y, so the top cap takes (centre, b, a).
      if (cap)
        mesh.triangles.push_back({centre, b, a});
      else
        mesh.triangles.push_back({centre, a, b});
    }
  }
  return mesh;
}

Mesh make_plane(double size, int tessellation) {
  check_tessellation(tessellation, 1, "plane");
  const int n = tessellation;
  Mesh mesh;
  // Index (i along x, k along z).
  for (int k = 0; k <= n; ++k)
    for (int i = 0; i <= n; ++i)
      add_vertex(mesh, {size * (double(i) / n - 0.5), 0, size * (double(k) / n - 0.5)}, {0, 1, 0});
  auto at = [&](int i, int k) { return static_cast<uint32_t>(k * (n + 1) + i); };
  // s runs along z, t along x: cross(d/dz, d/dx) = +y.
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i)
      add_quad(mesh, at(i, k), at(i, k + 1), at(i + 1, k + 1), at(i + 1, k));
  return mesh;
}

namespace {

// One mesh of an assimp scene as the import child sends it: positions and normals as x, y, z
// floats per vertex, and the vertex indices of its three-index faces (points and lines have
// nothing to shade), unchecked: the parent checks them (mesh_from_parts).
struct RawPart {
  std::vector<float> positions;
  std::vector<float> normals;
  std::vector<uint32_t> triangle_indices;
};

// Runs in the import child: only assimp and copying, so that everything that checks the data
// runs in the parent process, where the fuzzer's sanitizers and coverage see it.
std::vector<RawPart> import_with_assimp(const std::string& path) {
  Assimp::Importer importer;
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_GenSmoothNormals | aiProcess_PreTransformVertices);
  if (scene == nullptr) {
    throw SceneError(path + ": assimp could not read the mesh file: " + importer.GetErrorString());
  }
  std::vector<RawPart> parts;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* part = scene->mMeshes[m];
    RawPart raw;
    if (part != nullptr && part->HasPositions() && part->HasNormals()) {
      for (unsigned v = 0; v < part->mNumVertices; ++v) {
        const aiVector3D& p = part->mVertices[v];
        const aiVector3D& n = part->mNormals[v];
        raw.positions.insert(raw.positions.end(), {p.x, p.y, p.z});
        raw.normals.insert(raw.normals.end(), {n.x, n.y, n.z});
      }
      for (unsigned f = 0; f < part->mNumFaces; ++f) {
        const aiFace& face = part->mFaces[f];
        if (face.mNumIndices != 3) continue;
        raw.triangle_indices.insert(raw.triangle_indices.end(),
                                    {face.mIndices[0], face.mIndices[1], face.mIndices[2]});
      }
    }
    parts.push_back(std::move(raw));  // empty for a part without positions or normals
  }
  return parts;
}

// The shadesim mesh of the imported parts, all merged; throws SceneError naming the file.
Mesh mesh_from_parts(const std::string& path, const std::vector<RawPart>& parts) {
  Mesh mesh;
  for (size_t m = 0; m < parts.size(); ++m) {
    const RawPart& part = parts[m];
    const size_t vertices = part.positions.size() / 3;
    if (part.positions.size() % 3 != 0 || part.normals.size() != part.positions.size() ||
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
      // checked below, after all faces are known
      mesh.normals.push_back(
          {part.normals[3 * v], part.normals[3 * v + 1], part.normals[3 * v + 2]});
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
  // Generated normals can be zero or NaN at vertices of degenerate triangles only; give those the
  // area-weighted normal of their faces so every used vertex carries a unit normal.
  std::vector<Vec3> face_sum(mesh.positions.size());
  for (const auto& t : mesh.triangles) {
    const Vec3 area_normal = cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                                   mesh.positions[t[2]] - mesh.positions[t[0]]);
    for (uint32_t i : t) face_sum[i] += area_normal;
  }
  for (size_t i = 0; i < mesh.normals.size(); ++i) {
    Vec3 n = mesh.normals[i];
    if (!is_finite(n) || length(n) < 1e-12) n = face_sum[i];
    if (!is_finite(n) || length(n) < 1e-300) n = {0, 0, 1};  // only degenerate faces use it
    mesh.normals[i] = normalize(n);
  }
  return mesh;
}

// The import runs in a child process: Debian's assimp 5.2 dereferences null in its
// post-processing on some files (assimp-testmodels' own RAW models among them, found by
// tests/fuzz/fuzz_mesh.cpp) and may loop or allocate without bound on others. A crash, a
// runaway or an exhausted address space then ends the child, and the parent reports it as a
// SceneError naming the file instead of dying. The child sends the raw parts (or its
// SceneError's message) through a pipe.
constexpr rlim_t kImportCpuSeconds = 120;

bool write_all(int fd, const void* data, size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<size_t>(n);
  }
  return true;
}

template <typename T>
bool write_array(int fd, const std::vector<T>& items) {
  static_assert(std::is_trivially_copyable_v<T>, "sent as raw bytes");
  const uint64_t count = items.size();
  return write_all(fd, &count, sizeof count) &&
         write_all(fd, items.data(), items.size() * sizeof(T));
}

[[noreturn]] void import_in_child(const std::string& path, int fd) {
  // Crashes must end this child only, with the default action the parent can see, not a
  // handler the parent installed (sanitizers, libFuzzer).
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(sig, SIG_DFL);
  const rlimit cpu{kImportCpuSeconds, kImportCpuSeconds};
  setrlimit(RLIMIT_CPU, &cpu);
  const rlimit no_core{0, 0};  // a crash here is reported, not dumped
  setrlimit(RLIMIT_CORE, &no_core);
  const AddressSpaceCap cap(kImportAddressSpace);
  char kind = 'M';
  std::string message;
  std::vector<RawPart> parts;
  try {
    parts = import_with_assimp(path);
  } catch (const SceneError& e) {
    kind = 'E';
    message = e.what();
  } catch (const std::bad_alloc&) {
    kind = 'E';
    message = path + ": assimp ran out of memory reading the mesh file (more than " +
              std::to_string(kImportAddressSpace >> 30) + " GiB; a corrupt element count?)";
  } catch (const std::exception& e) {
    kind = 'E';
    message = path + ": assimp failed reading the mesh file: " + e.what();
  }
  bool ok = write_all(fd, &kind, 1);
  if (kind == 'E') {
    ok = ok && write_array(fd, std::vector<char>(message.begin(), message.end()));
  } else {
    const uint64_t count = parts.size();
    ok = ok && write_all(fd, &count, sizeof count);
    for (const RawPart& part : parts) {
      ok = ok && write_array(fd, part.positions) && write_array(fd, part.normals) &&
           write_array(fd, part.triangle_indices);
    }
  }
  ::close(fd);
  _exit(ok ? 0 : 3);
}

// Reads what import_in_child wrote; false when the bytes are short or inconsistent.
class PipeReader {
 public:
  explicit PipeReader(std::string bytes) : bytes_(std::move(bytes)) {}
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
  std::string bytes_;
  size_t at_ = 0;
};

std::string read_until_eof(int fd) {
  std::string bytes;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    bytes.append(buffer, static_cast<size_t>(n));
  }
  return bytes;
}

}  // namespace

Mesh load_mesh_file(const std::string& path) {
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw SceneError(path + ": cannot open mesh file (expected a readable file)");
  }
  int fds[2];
  if (::pipe(fds) != 0) {
    throw SceneError(path + ": cannot import the mesh file: pipe failed: " + std::strerror(errno));
  }
  std::fflush(nullptr);  // nothing buffered is written twice by the child
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw SceneError(path + ": cannot import the mesh file: fork failed: " + std::strerror(errno));
  }
  if (child == 0) {
    ::close(fds[0]);
    import_in_child(path, fds[1]);
  }
  ::close(fds[1]);
  const std::string bytes = read_until_eof(fds[0]);
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const std::string what = sig == SIGXCPU
                                 ? "ran past " + std::to_string(kImportCpuSeconds) + " s of CPU"
                                 : std::string("crashed (") + strsignal(sig) + ")";
    throw SceneError(path + ": assimp " + what +
                     " reading the mesh file (expected a well-formed mesh file; Debian's assimp "
                     "mishandles this one)");
  }
  PipeReader reader(bytes);
  char kind = 0;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !reader.read(&kind, 1)) {
    throw SceneError(path + ": mesh import process failed (exit status " +
                     std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
  }
  if (kind == 'E') {
    std::vector<char> message;
    if (!reader.read_array(message)) throw SceneError(path + ": mesh import process failed");
    throw SceneError(std::string(message.begin(), message.end()));
  }
  uint64_t count = 0;
  bool ok = kind == 'M' && reader.read(&count, sizeof count);
  std::vector<RawPart> parts;
  for (uint64_t m = 0; ok && m < count; ++m) {
    RawPart part;
    ok = reader.read_array(part.positions) && reader.read_array(part.normals) &&
         reader.read_array(part.triangle_indices);
    parts.push_back(std::move(part));
  }
  if (!ok || !reader.at_end())
    throw SceneError(path + ": mesh import process sent a malformed result");
  return mesh_from_parts(path, parts);
}

Mesh transform_mesh(const Mesh& mesh, const Transform& transform) {
  const double deg = kPi / 180.0;
  const Mat3 rotation = rotation_z(transform.rotate_deg.z * deg) *
                        rotation_y(transform.rotate_deg.y * deg) *
                        rotation_x(transform.rotate_deg.x * deg);
  const Vec3 s = transform.scale;
  if (s.x == 0 || s.y == 0 || s.z == 0)
    throw std::invalid_argument("transform scale must be non-zero");
  Mat3 scale, inverse_scale;
  scale.m[0][0] = s.x;
  scale.m[1][1] = s.y;
  scale.m[2][2] = s.z;
  inverse_scale.m[0][0] = 1 / s.x;
  inverse_scale.m[1][1] = 1 / s.y;
  inverse_scale.m[2][2] = 1 / s.z;
  const Mat3 linear = rotation * scale;
  // (R S)^-T = R^-T S^-T = R S^-1 for a rotation R and diagonal S.
  const Mat3 normal_matrix = rotation * inverse_scale;
  Mesh out;
  out.positions.reserve(mesh.positions.size());
  out.normals.reserve(mesh.normals.size());
  for (const Vec3& p : mesh.positions) out.positions.push_back(linear * p + transform.translate);
  for (const Vec3& n : mesh.normals) out.normals.push_back(normalize(normal_matrix * n));
  out.triangles = mesh.triangles;
  if (s.x * s.y * s.z < 0) {
    for (auto& t : out.triangles) std::swap(t[1], t[2]);
  }
  return out;
}

}  // namespace shadesim
