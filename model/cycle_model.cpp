#include "model/cycle_model.h"

#include <stdexcept>

#include "model/exponent_lut.h"
#include "model/schlick_divider.h"
#include "model/wpow_unit.h"

namespace shadesim {
namespace {
constexpr unsigned kOpMaterial = 0x01, kOpTriangle = 0x02, kOpSpan = 0x03, kOpTable = 0x04;
}

SlotTiming SlotTiming::of(const SpecularConfig& config) {
  switch (config.kind) {
    case SpecularUnitKind::kLut:
      return {ExponentLut::latency(config.lut), ExponentLut::cycles_per_pixel(config.lut)};
    case SpecularUnitKind::kSchlick:
      return {SchlickDivider::latency(config.schlick), SchlickDivider::cycles_per_pixel(config.schlick)};
    case SpecularUnitKind::kWpow:
      return {WpowUnit::latency(config.wpow), WpowUnit::cycles_per_pixel(config.wpow)};
    case SpecularUnitKind::kIdeal:
    default:
      return {0, 1};
  }
}

std::string to_string(CycleModel::Category c) {
  switch (c) {
    case CycleModel::Category::kPixel: return "pixel";
    case CycleModel::Category::kBackPressure: return "back_pressure";
    case CycleModel::Category::kUnitStall: return "unit_stall";
    case CycleModel::Category::kCommandGap: return "command_gap";
    case CycleModel::Category::kMaterial: return "material";
    case CycleModel::Category::kTable: return "table";
    case CycleModel::Category::kCommandWords: return "command_words";
    case CycleModel::Category::kSetupLoad: return "setup_load";
  }
  return "?";
}

std::vector<CycleBreakdown::Row> CycleBreakdown::rows() const {
  return {
      {"pixel", pixel, "a pixel left the unit"},
      {"back_pressure", back_pressure, "a pixel waited for pix_ready"},
      {"unit_stall", unit_stall, "an iterative specular unit held the next pixel"},
      {"command_gap", command_gap, "bubble: no command word was offered in time"},
      {"material", material, "bubble: MATERIAL drain, words and refill"},
      {"table", table, "bubble: TABLE words"},
      {"command_words", command_words, "bubble: TRIANGLE / END_FRAME / other words"},
      {"setup_load", setup_load, "bubble: span setup and engine load latency not hidden"},
  };
}

uint64_t CycleBreakdown::total() const {
  uint64_t t = 0;
  for (const Row& r : rows()) t += r.cycles;
  return t;
}

CycleModel::CycleModel(SlotTiming timing) : timing_(timing) {
  if (timing.latency < 0 || timing.interval < 1) {
    throw std::invalid_argument("CycleModel: slot latency must be >= 0 and interval >= 1, got latency " +
                                std::to_string(timing.latency) + ", interval " + std::to_string(timing.interval));
  }
  if (timing.interval > 1 && timing.latency != timing.interval) {
    throw std::invalid_argument("CycleModel: an iterative slot (interval " + std::to_string(timing.interval) +
                                ") must have latency == interval, got latency " + std::to_string(timing.latency));
  }
  if (!iterative()) dl_.resize(static_cast<size_t>(timing.latency));
  // Before the first cycle the port was "doing" nothing the pipe waited for: the first
  // span's latency is fill (setup_load).
  port_history_.assign(static_cast<size_t>(span_latency()), Category::kSetupLoad);
}

bool CycleModel::slot_empty() const {
  if (iterative()) return !inflight_.valid;
  for (const Pix& p : dl_) {
    if (p.valid) return false;
  }
  return true;
}

CycleModel::Category CycleModel::port_category(bool cmd_valid, unsigned op) const {
  if (!cmd_valid) return Category::kCommandGap;
  if (in_payload_) {
    switch (pay_op_) {
      case Payload::kMaterial: return Category::kMaterial;
      case Payload::kTable: return Category::kTable;
      default: return Category::kCommandWords;
    }
  }
  switch (op) {
    case kOpMaterial: return Category::kMaterial;
    case kOpTable: return Category::kTable;
    case kOpSpan: return Category::kSetupLoad;
    default: return Category::kCommandWords;
  }
}

CycleModel::Edge CycleModel::clock(bool cmd_valid, uint64_t word, bool pix_ready) {
  Edge e;
  // ---- combinational, from the state before the edge (same equations as the RTL) ----
  const bool adv = !pix_.valid || pix_ready;
  const bool busy = busy_ > 0;
  const bool emit = run_ && adv && !busy;
  const bool last_pix = rem_ == 1;
  const bool load_eng = s_[2].valid && (!run_ || (emit && last_pix));
  const bool s3_free = !s_[2].valid || load_eng;
  const bool s2_move = s_[1].valid && s3_free;
  const bool s1_move = s_[0].valid && (!s_[1].valid || s2_move);
  const bool s1_free = !s_[0].valid || s1_move;
  const bool empty = datapath_empty();

  const unsigned op = static_cast<unsigned>(word >> 56) & 0xFF;
  const unsigned count = static_cast<unsigned>(word & 0xFFFF);
  bool hdr_ready = true;
  if (op == kOpMaterial || op == kOpTable) hdr_ready = empty;
  if (op == kOpSpan) hdr_ready = s1_free;
  e.cmd_ready = in_payload_ || hdr_ready;
  e.cmd_fire = cmd_valid && e.cmd_ready;
  const bool hdr_fire = e.cmd_fire && !in_payload_;
  const bool pay_fire = e.cmd_fire && in_payload_;
  const bool span_fire = hdr_fire && op == kOpSpan;

  e.pix_fire = pix_.valid && pix_ready;
  e.pix_eor = pix_.eor;
  e.pix_x = pix_.x;
  e.pix_y = pix_.y;

  // ---- where this cycle went ----
  const size_t slot = static_cast<size_t>(cycle_ % port_history_.size());
  if (e.pix_fire) {
    e.category = Category::kPixel;
  } else if (pix_.valid) {
    e.category = Category::kBackPressure;
  } else if (iterative() && inflight_.valid) {
    e.category = Category::kUnitStall;
  } else {
    e.category = port_history_[slot];  // the port's category span_latency() cycles ago
  }
  port_history_[slot] = port_category(cmd_valid, op);
  ++cycle_;

  // ---- the edge: engines -> slot -> pix register ----
  const Pix from_engines{run_, x_, y_, last_ && last_pix};
  if (iterative()) {
    if (adv && !busy) {
      pix_ = inflight_;
      inflight_ = from_engines;  // valid == emit
    } else if (adv) {
      pix_.valid = false;
    }
    if (emit) busy_ = timing_.interval - 1;
    else if (busy_ > 0) --busy_;
  } else if (adv) {
    if (dl_.empty()) {
      pix_ = from_engines;
    } else {
      pix_ = dl_.back();
      for (size_t i = dl_.size() - 1; i > 0; --i) dl_[i] = dl_[i - 1];
      dl_[0] = from_engines;
    }
  }
  if (load_eng) {
    run_ = true;
    rem_ = static_cast<unsigned>(s_[2].len);
    x_ = s_[2].x0;
    y_ = s_[2].y;
    last_ = s_[2].last;
  } else if (emit) {
    if (last_pix) run_ = false;
    --rem_;
    ++x_;
  }
  if (s2_move) s_[2] = s_[1];
  else if (load_eng) s_[2].valid = false;
  if (s1_move) s_[1] = s_[0];
  else if (s2_move) s_[1].valid = false;
  if (span_fire) {
    s_[0].valid = true;
    s_[0].y = static_cast<int>((word >> 32) & 0xFFFF);
    s_[0].x0 = static_cast<int>((word >> 16) & 0xFFFF);
    s_[0].len = static_cast<int>(count);
    s_[0].last = ((word >> 55) & 1) != 0;
  } else if (s1_move) {
    s_[0].valid = false;
  }

  if (hdr_fire) {
    pay_idx_ = 0;
    pay_last_ = (count - 1) & 0xFFFF;
    switch (op) {
      case kOpMaterial: pay_op_ = Payload::kMaterial; in_payload_ = count != 0; break;
      case kOpTriangle: pay_op_ = Payload::kTriangle; in_payload_ = count != 0; break;
      case kOpTable: pay_op_ = Payload::kTable; in_payload_ = count != 0; break;
      default: pay_op_ = Payload::kSkip; in_payload_ = false; break;
    }
  } else if (pay_fire) {
    if (pay_idx_ == pay_last_) in_payload_ = false;
    pay_idx_ = (pay_idx_ + 1) & 0xFFFF;
  }
  return e;
}

CycleRun CycleModel::run(const std::vector<uint64_t>& words, const Stimulus& stim, SlotTiming timing) {
  CycleModel m(timing);
  CommandDriver driver(words, stim);
  CycleRun r;
  r.words = words.size();
  uint64_t cycle = 0;
  CycleBreakdown& b = r.breakdown;
  while (!driver.done() || !m.idle()) {
    const Edge e = m.clock(driver.valid(), driver.word(), stim.pix_ready(cycle));
    driver.clock(e.cmd_fire);
    switch (e.category) {
      case Category::kPixel: ++b.pixel; break;
      case Category::kBackPressure: ++b.back_pressure; break;
      case Category::kUnitStall: ++b.unit_stall; break;
      case Category::kCommandGap: ++b.command_gap; break;
      case Category::kMaterial: ++b.material; break;
      case Category::kTable: ++b.table; break;
      case Category::kCommandWords: ++b.command_words; break;
      case Category::kSetupLoad: ++b.setup_load; break;
    }
    if (e.pix_fire) {
      ++r.pixels;
      if (e.pix_eor) r.scanlines.push_back({e.pix_y, cycle, e.pix_x});
    }
    ++cycle;
  }
  r.cycles = cycle;
  return r;
}

}  // namespace shadesim
