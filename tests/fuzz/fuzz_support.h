// Shared helpers of the libFuzzer harnesses: the parsers under test read files, so each input is
// written to a file in a private directory first, and any exception that is not the parser's
// documented error type must end the run as a crash (libFuzzer reports std::terminate).
#pragma once

#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "host/mesh.h"

namespace shadesim::fuzz {

// A directory of this process only (mkdtemp), so parallel fuzzers and ctest -j never share
// files; removed when the fuzzer exits normally (after a crash it stays, beside the artifact).
// The name lives in a plain array: the exit handler runs after static strings are destroyed.
inline const std::string& private_dir() {
  static char name[] = "/tmp/shadesim-fuzz-XXXXXX";
  static const std::string dir = [] {
    if (mkdtemp(name) == nullptr) {
      std::perror("shadesim fuzz: mkdtemp");
      std::abort();
    }
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(name, ignored);
    });
    return std::string(name);
  }();
  return dir;
}

inline std::string write_input(const std::string& file_name, const uint8_t* data, size_t size) {
  std::string path = private_dir() + "/" + file_name;  // returned: moved
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) {
    std::perror("shadesim fuzz: write input");
    std::abort();
  }
  return path;
}

// A documented error must say something: an empty what() is no clear error.
inline void require_message(const std::exception& e) {
  if (std::string(e.what()).empty()) {
    std::fprintf(stderr, "shadesim fuzz: documented error with an empty message\n");
    std::abort();
  }
}

[[noreturn]] inline void fail(const char* what) {
  std::fprintf(stderr, "shadesim fuzz: %s\n", what);
  std::abort();
}

// What a loaded mesh promises (host/mesh.h): triangles that index its vertices, one unit normal
// per vertex.
inline void check_mesh(const shadesim::Mesh& mesh) {
  if (mesh.triangles.empty() || mesh.normals.size() != mesh.positions.size()) {
    fail("the mesh loader returned an empty mesh or unmatched normals");
  }
  for (const auto& t : mesh.triangles) {
    for (uint32_t i : t) {
      if (i >= mesh.positions.size()) fail("triangle index out of range");
    }
  }
  for (const shadesim::Vec3& n : mesh.normals) {
    if (!(std::fabs(shadesim::length(n) - 1.0) < 1e-6)) {
      fail("the mesh loader returned a normal that is not unit length");
    }
  }
}

}  // namespace shadesim::fuzz
