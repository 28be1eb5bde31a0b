// The key of a cached derivation (sim/engines/derivation_cache.h): everything derive_config's
// result depends on, by content. derive_config reads the scene files, the mesh files they name and
// its DeriveOptions, and computes with this shadesim's code; nothing else (no clock, no tool, no
// environment). So the key hashes (ContentHash, XXH3-128):
//   - a format tag, bumped when the entry's meaning changes in a way the code's hash cannot show;
//   - the executable's digest (sim/eda/common/build_identity.h): the code;
//   - the DeriveOptions, canonically (derive_options_json: every field, keys sorted);
//   - each scene in order: its path as given (the reasons name it: "from scenes/sphere.json"),
//     its bytes, and for each object of "type": "mesh" its file, resolved as load_scene resolves
//     it (mesh_file_path), and that file's bytes.
// A mesh format that reads side files (a .gltf's buffers) is keyed by the named file alone; the
// shipped scenes' meshes (.blend, .obj) are whole in one file.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "derive/derive_config.h"

namespace shadesim {

// The implicit move is noexcept in both members; clang-tidy 14 follows nlohmann::json's move
// into code that cannot throw there.
// NOLINTNEXTLINE(bugprone-exception-escape): see above
struct DerivationKey {
  std::string hex;        // 32 hex digits: the entry's file name, and checked inside it
  nlohmann::json inputs;  // what was hashed, readable: format, build, options, scenes and meshes
};

// Every DeriveOptions field as JSON (objects' keys sorted, so dump() is canonical); a specular
// unit as config_to_json writes a UnitConfig's "specular". A field added to DeriveOptions must
// be added here, or derivations that differ in it would share an entry.
nlohmann::json derive_options_json(const DeriveOptions& options);

// Throws std::runtime_error when a scene or mesh file cannot be read, a scene is no JSON or the
// executable cannot be read: the caller derives without the cache (derive_config reports a bad
// scene in its own words).
DerivationKey derivation_key(const std::vector<std::string>& scene_paths,
                             const DeriveOptions& options);

}  // namespace shadesim
