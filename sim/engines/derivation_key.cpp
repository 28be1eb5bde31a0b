#include "sim/engines/derivation_key.h"

#include <stdexcept>

#include "host/scene.h"
#include "model/command_stream.h"
#include "model/text_file.h"
#include "sim/eda/common/build_identity.h"
#include "sim/eda/common/content_hash.h"

namespace shadesim {
namespace {

// Bumped when what an entry holds, or how it is read, changes in a way the executable's digest
// cannot show (the digest covers all of the code, so this is for the entry's own layout).
constexpr const char* kDerivationKeyFormat = "shadesim-derivation-cache 1";

// A specular unit in the words of config_to_json (every unit's every field), so a unit added to
// model/specular_units.cpp is keyed without touching this file.
nlohmann::json specular_json(const SpecularConfig& s) {
  UnitConfig u;
  u.specular = s;
  return nlohmann::json::parse(config_to_json(u)).at("specular");
}

template <class T, class F>
nlohmann::json optional_json(const std::optional<T>& v, F&& to_json) {
  return v ? nlohmann::json(to_json(*v)) : nlohmann::json(nullptr);
}

// The mesh files a scene's text names, resolved as load_scene resolves them. A scene that is no
// JSON fails here; objects that are not well-formed are left to derive_config to report.
std::vector<std::string> mesh_files(const std::string& scene_path, const std::string& text) {
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(scene_path + ": not JSON (" + e.what() + ")");
  }
  std::vector<std::string> out;
  if (!root.is_object() || !root.contains("objects") || !root["objects"].is_array()) return out;
  for (const auto& o : root["objects"]) {
    if (!o.is_object() || o.value("type", nlohmann::json()) != "mesh") continue;
    const auto file = o.find("file");
    if (file == o.end() || !file->is_string() || file->get<std::string>().empty()) continue;
    out.push_back(mesh_file_path(scene_path, file->get<std::string>()));
  }
  return out;
}

std::string bytes_digest(const std::string& bytes) { return ContentHash().add(bytes).hex(); }

}  // namespace

nlohmann::json derive_options_json(const DeriveOptions& o) {
  nlohmann::json fallbacks = nlohmann::json::array();
  for (const SpecularConfig& s : o.ideal_fallbacks) fallbacks.push_back(specular_json(s));
  auto self = [](auto v) { return v; };
  return {
      {"budget_lsb", optional_json(o.budget_lsb, self)},
      {"out_bits", o.out_bits},
      {"ideal_substitute", specular_json(o.ideal_substitute)},
      {"ideal_fallbacks", fallbacks},
      {"search_named_units", o.search_named_units},
      {"specular_trial", optional_json(o.specular_trial, specular_json)},
      {"widen",
       {o.widen.spec_colour, o.widen.specular_out, o.widen.series_coef, o.widen.exact_before,
        o.widen.exact_after}},
      {"max_depth", o.max_depth},
      {"hold_gate", o.hold_gate},
      {"port_words", optional_json(o.port_words, self)},
      {"tri_queue", optional_json(o.tri_queue, self)},
      {"span_setup", optional_json(o.span_setup, [](SpanSetupSite s) { return to_string(s); })},
      {"diffuse_colour",
       optional_json(o.diffuse_colour, [](DiffuseColour d) { return to_string(d); })},
      {"lanes", o.lanes},
      {"max_cycles_per_pixel", optional_json(o.max_cycles_per_pixel, self)},
      // Not `threads`: the derivation is the same for any thread count (prepared_scene_test).
  };
}

DerivationKey derivation_key(const std::vector<std::string>& scene_paths,
                             const DeriveOptions& options) {
  DerivationKey k;
  const std::string build = executable_digest();
  const nlohmann::json opts = derive_options_json(options);
  ContentHash h;
  h.add(kDerivationKeyFormat).add(build).add(opts.dump());
  nlohmann::json scenes = nlohmann::json::array();
  h.add(std::to_string(scene_paths.size()));
  for (const std::string& path : scene_paths) {
    const std::string text = read_text_file(path);
    const std::vector<std::string> meshes = mesh_files(path, text);
    h.add(path).add(text).add(std::to_string(meshes.size()));
    nlohmann::json mesh_list = nlohmann::json::array();
    for (const std::string& m : meshes) {
      const std::string bytes = read_text_file(m);
      h.add(m).add(bytes);
      mesh_list.push_back({{"file", m}, {"xxh3", bytes_digest(bytes)}});
    }
    scenes.push_back({{"path", path}, {"xxh3", bytes_digest(text)}, {"meshes", mesh_list}});
  }
  k.hex = h.hex();
  k.inputs = {{"format", kDerivationKeyFormat},
              {"executable", build},
              {"options", opts},
              {"scenes", scenes}};
  return k;
}

}  // namespace shadesim
