#include "sim/engines/derivation_cache.h"

#include <cstdlib>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "model/command_stream.h"
#include "model/text_file.h"
#include "sim/eda/common/build_paths.h"
#include "sim/eda/common/content_hash.h"
#include "sim/eda/common/flow_tools.h"
#include "sim/engines/derivation_key.h"
#include "sim/engines/derived_json.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

// The unit's own hash in an entry: a unit edited by hand under an intact key is caught.
std::string unit_digest(const UnitConfig& unit) {
  return ContentHash().add(config_to_json(unit)).hex();
}

// The entry's derivation when it is the one `key` names and whole; nullopt when there is none,
// and, with a warning, when it cannot be used.
std::optional<DerivedConfig> read_derivation_entry(const fs::path& path, const DerivationKey& key,
                                                   std::ostream& warnings) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return std::nullopt;
  try {
    const std::string text = read_text_file(path.string());
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
      throw std::runtime_error(std::string("not JSON: ") + e.what());
    }
    const nlohmann::json& cache = j.at("derivation").at("cache");
    const std::string found = cache.at("key").get<std::string>();
    if (found != key.hex)
      throw std::runtime_error("it holds the derivation of key " + found + ", not " + key.hex);
    DerivedConfig d = derived_from_json(j, path.string());
    if (cache.at("unit_xxh3").get<std::string>() != unit_digest(d.config))
      throw std::runtime_error("its unit does not match the unit's hash beside it");
    return d;
  } catch (const std::exception& e) {
    warnings << "shadesim: warning: unit cache entry " << path.string() << " is unusable ("
             << e.what() << "); deriving the unit again and overwriting it\n";
    return std::nullopt;
  }
}

void write_derivation_entry(const fs::path& path, const DerivationKey& key,
                            const DerivedConfig& derived) {
  nlohmann::json j = derived_to_json(derived);
  j["derivation"]["cache"] = {
      {"key", key.hex}, {"unit_xxh3", unit_digest(derived.config)}, {"inputs", key.inputs}};
  fs::create_directories(path.parent_path());
  flow_tools::write_atomically(path, j.dump(2) + '\n');
}

}  // namespace

std::string default_unit_cache_dir() {
  if (const char* v = std::getenv("SHADESIM_UNIT_CACHE"); v && *v)
    return std::string(v) == "off" ? std::string() : std::string(v);
  std::error_code ec;
  if (fs::is_directory(binary_dir(), ec)) return (fs::path(binary_dir()) / "unit-cache").string();
  // XDG's rule: a relative XDG_CACHE_HOME is ignored.
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x == '/')
    return (fs::path(x) / "shadesim").string();
  if (const char* home = std::getenv("HOME"); home && *home)
    return (fs::path(home) / ".cache" / "shadesim").string();
  return "";
}

std::string CachedDerivation::origin() const {
  if (reused) return "cached derivation, " + entry;
  return entry.empty() ? "derived" : "derived, cached as " + entry;
}

namespace {

CachedDerivation cached(const std::vector<std::string>& scene_paths, const DeriveOptions& options,
                        const std::string& cache_dir, std::ostream& warnings,
                        const std::function<DerivedConfig()>& derive) {
  CachedDerivation out;
  std::optional<DerivationKey> key;
  std::string unkeyed;  // why there is no key, told only if the derivation succeeds
  if (!cache_dir.empty()) {
    try {
      key = derivation_key(scene_paths, options);
    } catch (const std::exception& e) {
      unkeyed = e.what();
    }
  }
  const fs::path entry = key ? fs::path(cache_dir) / (key->hex + ".json") : fs::path();
  if (key) {
    if (std::optional<DerivedConfig> d = read_derivation_entry(entry, *key, warnings)) {
      out.derived = std::move(*d);
      out.entry = entry.string();
      out.reused = true;
      return out;
    }
  }
  out.derived = derive();
  if (!unkeyed.empty())
    warnings << "shadesim: warning: the derived unit is not cached (" << unkeyed << ")\n";
  if (!key) return out;
  try {
    write_derivation_entry(entry, *key, out.derived);
    out.entry = entry.string();
  } catch (const std::domain_error&) {
    // A measurement JSON cannot hold (an image with no pixel): derived each time, as before.
  } catch (const std::exception& e) {
    warnings << "shadesim: warning: cannot write unit cache entry " << entry.string() << " ("
             << e.what() << ")\n";
  }
  return out;
}

}  // namespace

CachedDerivation cached_derive_config(const std::vector<std::string>& scene_paths,
                                      const DeriveOptions& options, const std::string& cache_dir,
                                      std::ostream& warnings) {
  return cached(scene_paths, options, cache_dir, warnings,
                [&] { return derive_config(scene_paths, options); });
}

CachedDerivation cached_derive_config(const FrameSet& frames, const DeriveOptions& options,
                                      const std::string& cache_dir, std::ostream& warnings) {
  std::vector<std::string> paths;
  for (size_t i = 0; i < frames.size(); ++i) paths.push_back(frames.path(i));
  return cached(paths, options, cache_dir, warnings,
                [&] { return derive_config(frames, options); });
}

}  // namespace shadesim
