#include "model/cycle_model.h"

#include <stdexcept>

#include "model/specular_units.h"
#include "model/start_bank.h"
#include "model/start_packing.h"

namespace shadesim {

SlotTiming SlotTiming::of(const SpecularConfig& config) {
  const SpecularUnitDescriptor& unit = specular_unit(config.kind);
  return {unit.latency(config), unit.interval(config)};
}

CycleConfig CycleConfig::of(const UnitConfig& config) {
  CycleConfig c(SlotTiming::of(config.specular), config.port_words, config.tri_queue, config.lanes);
  c.material_buffers = config.material_buffers;
  c.host_setup = config.host_setup();
  if (c.host_setup) c.start_words = StartLayout::of(config).words;
  c.start_depth = config.start_depth;
  c.combine_stages = config.combine_stages;
  return c;
}

std::string to_string(CycleModel::Category c) {
  switch (c) {
    case CycleModel::Category::kPixel:
      return "pixel";
    case CycleModel::Category::kBackPressure:
      return "back_pressure";
    case CycleModel::Category::kUnitStall:
      return "unit_stall";
    case CycleModel::Category::kCommandGap:
      return "command_gap";
    case CycleModel::Category::kMaterial:
      return "material";
    case CycleModel::Category::kTable:
      return "table";
    case CycleModel::Category::kCommandWords:
      return "command_words";
    case CycleModel::Category::kSetupLoad:
      return "setup_load";
  }
  return "?";
}

std::vector<CycleBreakdown::Row> CycleBreakdown::rows() const {
  return {
      {"pixel", pixel, "a pixel beat (1..lanes pixels) left the unit"},
      {"back_pressure", back_pressure, "a pixel beat waited for pix_ready"},
      {"unit_stall", unit_stall, "an iterative specular unit held the next pixel"},
      {"command_gap", command_gap, "bubble: no command word was offered in time"},
      {"material", material, "bubble: MATERIAL drain, words and refill"},
      {"table", table, "bubble: TABLE words"},
      {"command_words", command_words,
       "bubble: TRIANGLE / span start values / END_FRAME / other words"},
      {"setup_load", setup_load, "bubble: span setup and engine load latency not hidden"},
  };
}

uint64_t CycleBreakdown::total() const {
  uint64_t t = 0;
  for (const Row& r : rows()) t += r.cycles;
  return t;
}

namespace {

// The configuration's checks, before any module is built from it.
const CycleConfig& checked(const CycleConfig& unit) {
  if (unit.host_setup &&
      (unit.tri_queue != 1 || unit.start_depth < 1 ||
       unit.start_depth > static_cast<int>(StartBank::kMaxDepth) || unit.start_words < 1)) {
    throw std::invalid_argument(
        "CycleModel: host span setup needs tri_queue 1, start_depth 1 or 2 and start_words >= 1");
  }
  if (unit.material_buffers != 1 && unit.material_buffers != 2) {
    throw std::invalid_argument("CycleModel: material_buffers must be 1 or 2, got " +
                                std::to_string(unit.material_buffers));
  }
  if (unit.lanes != 1 && unit.lanes != 2 && unit.lanes != 4) {
    throw std::invalid_argument("CycleModel: lanes must be 1, 2 or 4, got " +
                                std::to_string(unit.lanes));
  }
  if (unit.tri_queue < 1 || unit.tri_queue > SpanQueue::kMaxBanks) {
    throw std::invalid_argument("CycleModel: tri_queue must be 1..8, got " +
                                std::to_string(unit.tri_queue));
  }
  const SlotTiming& timing = unit.slot;
  if (unit.port_words != 1 && unit.port_words != 2 && unit.port_words != 4 &&
      unit.port_words != 8) {
    throw std::invalid_argument("CycleModel: port_words must be 1, 2, 4 or 8, got " +
                                std::to_string(unit.port_words));
  }
  if (unit.combine_stages < 0 || unit.combine_stages > 2) {
    throw std::invalid_argument("CycleModel: combine_stages must be 0, 1 or 2, got " +
                                std::to_string(unit.combine_stages));
  }
  if (timing.latency < 0 || timing.interval < 1) {
    throw std::invalid_argument(
        "CycleModel: slot latency must be >= 0 and interval >= 1, got latency " +
        std::to_string(timing.latency) + ", interval " + std::to_string(timing.interval));
  }
  if (timing.interval > 1 && timing.latency != timing.interval) {
    throw std::invalid_argument(
        "CycleModel: an iterative slot (interval " + std::to_string(timing.interval) +
        ") must have latency == interval, got latency " + std::to_string(timing.latency));
  }
  return unit;
}

}  // namespace

CycleModel::CycleModel(CycleConfig timing)
    : latency_(checked(timing).slot.latency + timing.combine_stages),
      queued_(timing.tri_queue > 1),
      host_(timing.host_setup),
      mat_banked_(timing.material_buffers == 2),
      decoder_(static_cast<unsigned>(timing.port_words), queued_, mat_banked_, host_,
               static_cast<unsigned>(timing.start_words)),
      span_source_(host_, timing.tri_queue, static_cast<unsigned>(timing.start_depth)),
      mat_(host_),
      engines_(static_cast<unsigned>(timing.lanes)),
      slots_(timing.slot.interval),
      meta_(timing.slot.latency, timing.slot.interval > 1),
      combine_(timing.combine_stages, false) {
  // Before the first cycle the port was "doing" nothing the pipe waited for: the first
  // span's latency is fill (setup_load).
  port_history_.assign(static_cast<size_t>(span_latency()), Category::kSetupLoad);
}

}  // namespace shadesim
