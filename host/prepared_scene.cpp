#include "host/prepared_scene.h"

#include <chrono>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace shadesim {

bool PrepareKey::operator<(const PrepareKey& o) const {
  return std::tie(budget_lsb, max_depth, out_bits) <
         std::tie(o.budget_lsb, o.max_depth, o.out_bits);
}

PreparedScene::PreparedScene(std::string path, const PrepareKey& key)
    : path_(std::move(path)), key_(key) {
  const auto t0 = std::chrono::steady_clock::now();
  scene_ = load_scene(path_);
  timings_.load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  SetupOptions setup_options;
  setup_options.budget_lsb = key_.budget_lsb;
  setup_options.max_depth = key_.max_depth;
  setup_options.output_bits = key_.out_bits;
  prepare_geometry(scene_, setup_options, project_, setup_, visibility_, timings_);
}

const ReferenceImage& PreparedScene::reference(int channels) const {
  if (channels != 1 && channels != 3) {
    throw std::invalid_argument("reference: channels must be 1 or 3, got " +
                                std::to_string(channels));
  }
  const std::lock_guard<std::mutex> lock(reference_mutex_);
  std::unique_ptr<ReferenceImage>& slot = references_[channels == 1 ? 0 : 1];
  if (!slot) {
    slot = std::make_unique<ReferenceImage>(
        render_reference(setup_.triangles, visibility_, scene_, channels));
  }
  return *slot;
}

namespace {

// `unit` as prepare_frame takes a fixed unit, checked against the scene and the key.
UnitConfig checked_unit(const std::string& path, const Scene& scene, const PrepareKey& key,
                        const UnitConfig& unit) {
  if (unit.out_bits != key.out_bits) {
    throw std::invalid_argument(
        path + ": prepared for " + std::to_string(key.out_bits) +
        "-bit output, asked to encode for out_bits=" + std::to_string(unit.out_bits));
  }
  FrameOptions fo;
  fo.base = unit;
  fo.fixed_unit = true;
  return frame_unit(scene, path, fo);
}

}  // namespace

EncodedFrame PreparedScene::encode(const UnitConfig& unit) const {
  const UnitConfig config = checked_unit(path_, scene_, key_, unit);
  return encode_frame(scene_, config, setup_, visibility_);
}

EncodeStats PreparedScene::encode_chunks(const UnitConfig& unit, const ChunkSink& sink) const {
  const UnitConfig config = checked_unit(path_, scene_, key_, unit);
  return encode_frame_chunks(scene_, config, setup_, visibility_, sink);
}

const PreparedScene& PreparedScenes::at(const std::string& path, const PrepareKey& key) {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::shared_ptr<PreparedScene>& slot = scenes_[{path, key}];
  if (!slot) slot = std::make_shared<PreparedScene>(path, key);
  return *slot;
}

FrameSet::FrameSet(PreparedScenes& store, const std::vector<std::string>& paths,
                   const PrepareKey& key) {
  for (const auto& path : paths) frames_.push_back(&store.at(path, key));
}

size_t PreparedScenes::prepared() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return scenes_.size();
}

}  // namespace shadesim
