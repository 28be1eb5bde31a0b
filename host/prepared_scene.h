// A scene prepared once for every unit a command tries. Loading, transform, clipping,
// rasterization, visibility and triangle setup in double depend on the scene, the Taylor budget,
// the subdivision limit and the output width, never on the unit's widths or structure; so the
// derivation, the accuracy checks and the throughput choice prepare each scene once and then
// only re-quantize (encode) and re-shade it per candidate unit. The double reference image is
// computed once per channel count.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "host/encode.h"
#include "host/frame.h"
#include "host/metrics.h"
#include "host/raster.h"
#include "host/reference.h"
#include "host/scene.h"
#include "host/triangle_setup.h"
#include "model/unit_config.h"

namespace shadesim {

// What a prepared frame depends on besides the scene file.
struct PrepareKey {
  std::optional<double> budget_lsb;  // unset: the scene's error_budget_lsb
  int max_depth = 12;
  int out_bits = 8;  // setup's budget is in LSBs of this output width
  bool operator<(const PrepareKey& o) const;
};

class PreparedScene {
 public:
  // Throws SceneError for bad scene or mesh input.
  PreparedScene(std::string path, const PrepareKey& key);
  PreparedScene(const PreparedScene&) = delete;
  PreparedScene& operator=(const PreparedScene&) = delete;

  const std::string& path() const { return path_; }
  const PrepareKey& key() const { return key_; }
  const Scene& scene() const { return scene_; }
  const ProjectStats& project() const { return project_; }
  const SetupResult& setup() const { return setup_; }
  const Visibility& visibility() const { return visibility_; }
  const FrameTimings& timings() const { return timings_; }

  // The double-precision reference for a unit of `channels` (1 or 3); computed on first use.
  // Safe to call from several threads.
  const ReferenceImage& reference(int channels) const;

  // The frame's command stream on exactly `unit` (validated). Throws std::invalid_argument
  // naming the scene when the unit cannot shade it (lights, channels, xy_bits) or when its
  // out_bits differ from the key's (setup's budget would be in other LSBs).
  EncodedFrame encode(const UnitConfig& unit) const;
  // The same stream a chunk at a time (encode_frame_chunks): for a consumer that need not hold
  // the whole frame. Returns its stats.
  EncodeStats encode_chunks(const UnitConfig& unit, const ChunkSink& sink) const;

  // scene_error's result for `unit`, measured once: the derivation and config's checks ask for
  // the same unit more than once. `measure` runs outside the lock.
  template <class Measure>
  ErrorStats error_on(const UnitConfig& unit, Measure measure) const {
    const std::string key = config_to_json(unit);
    {
      const std::lock_guard<std::mutex> lock(memo_mutex_);
      if (const auto at = errors_.find(key); at != errors_.end()) return at->second;
    }
    const ErrorStats e = measure();
    const std::lock_guard<std::mutex> lock(memo_mutex_);
    errors_.emplace(key, e);
    return e;
  }

 private:
  std::string path_;
  PrepareKey key_;
  Scene scene_;
  ProjectStats project_;
  SetupResult setup_;
  Visibility visibility_;
  FrameTimings timings_;
  mutable std::mutex reference_mutex_;
  mutable std::array<std::unique_ptr<ReferenceImage>, 2> references_;  // 1 channel, 3 channels
  mutable std::mutex memo_mutex_;
  mutable std::map<std::string, ErrorStats> errors_;  // by the unit's JSON
};

// The scenes one command shades, each prepared on first use and then shared: a derivation
// asks for the same scene for every candidate unit. Safe to call from several threads.
class PreparedScenes {
 public:
  const PreparedScene& at(const std::string& path, const PrepareKey& key);
  // How many frames were prepared (each once), for tests and progress lines.
  size_t prepared() const;

 private:
  mutable std::mutex mutex_;
  std::map<std::pair<std::string, PrepareKey>, std::shared_ptr<PreparedScene>> scenes_;
};

// A command's scenes, prepared, in the order given: what the derivation, the accuracy checks and
// the throughput choice iterate. The frames belong to a PreparedScenes (or the caller) that
// outlives the set.
class FrameSet {
 public:
  FrameSet(PreparedScenes& store, const std::vector<std::string>& paths, const PrepareKey& key);
  explicit FrameSet(const PreparedScene& frame) : frames_{&frame} {}
  size_t size() const { return frames_.size(); }
  const PreparedScene& at(size_t i) const { return *frames_.at(i); }
  const std::string& path(size_t i) const { return at(i).path(); }

 private:
  std::vector<const PreparedScene*> frames_;
};

}  // namespace shadesim
