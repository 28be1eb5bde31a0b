// The input ports as the harness drives them, replayed without the RTL (sim/eda/power/activity.h,
// port_stimulus): an independent count of the port toggles the traced co-simulation reports,
// and the share of cmd_data_i's toggles that is the harness's idle noise.
#include <array>
#include <string>
#include <vector>

#include "model/cycle_model.h"
#include "model/shade_unit.h"
#include "sim/eda/power/activity.h"
#include "sim/harness/cosim.h"

namespace shadesim {
namespace activity_ports_impl {

// Toggles of a bus of 64-bit words, one value per call, the first value the baseline.
class BusToggles {
 public:
  explicit BusToggles(int words)
      : prev_(static_cast<size_t>(words), 0), count_(64 * prev_.size()) {}
  void see(const uint64_t* value) {
    for (size_t k = 0; k < prev_.size(); ++k) {
      if (seen_)
        for (uint64_t d = prev_[k] ^ value[k]; d != 0; d &= d - 1) ++count_[64 * k + ctz(d)];
      prev_[k] = value[k];
    }
    seen_ = true;
  }
  uint64_t total() const {
    uint64_t t = 0;
    for (uint64_t c : count_) t += c;
    return t;
  }
  const std::vector<uint64_t>& counts() const { return count_; }

 private:
  static size_t ctz(uint64_t d) { return static_cast<size_t>(__builtin_ctzll(d)); }
  std::vector<uint64_t> prev_;
  std::vector<uint64_t> count_;
  bool seen_ = false;
};

// The stand-in's pix_colour_o: lane j of a beat is pixels[first + j], channel c in bits
// [c * out_bits +: out_bits] of the lane's channels * out_bits (sim/harness/cosim.h).
uint64_t stand_in_colour(const std::vector<PixelOut>& pixels, size_t first, const UnitConfig& u,
                         int lsb, int width) {
  const int lane_width = u.channels * u.out_bits;
  const size_t lane = static_cast<size_t>(lsb / lane_width);
  if (first + lane >= pixels.size()) return 0;
  uint64_t v = 0;
  for (int c = 0; c < u.channels; ++c)
    v |= static_cast<uint64_t>(pixels[first + lane].colour[static_cast<size_t>(c)])
         << (c * u.out_bits);
  return port_bits(v, lsb % lane_width, width);
}

// What a correct RTL shows on the cycle the cycle model says `e` of.
Lockstep::Sample sample_of_edge(const CycleModel::Edge& e) {
  Lockstep::Sample s;
  s.cmd_ready = e.cmd_ready;
  s.pix_valid = e.pix_fire;
  s.pix_x = static_cast<uint64_t>(e.pix_x);
  s.pix_y = static_cast<uint64_t>(e.pix_y);
  s.pix_mask = e.pix_fire ? (uint64_t{1} << e.pix_count) - 1 : 0;
  s.pix_eor = e.pix_eor;
  return s;
}

}  // namespace activity_ports_impl

PortStimulus port_stimulus(const UnitConfig& unit, const CommandStream& stream) {
  using activity_ports_impl::BusToggles;
  CosimJob job;
  job.config.name = "power";
  job.config.unit = unit;
  job.stream = stream;
  job.stim = Stimulus{};  // seed 1, no gaps, no back-pressure: what scene_activity runs
  Lockstep lockstep(job);
  CycleModel dut(CycleConfig::of(unit));
  dut.track_categories(false);
  const std::vector<PixelOut> pixels = ShadeUnit(unit).run(stream);
  BusToggles data(unit.port_words), held(unit.port_words);
  std::array<uint64_t, 8> last_beat{};
  bool valid = false, ready = false;
  PortStimulus out;
  out.ports["cmd_valid_i"] = out.ports["pix_ready_i"] = 0;
  size_t next = 0;
  for (uint64_t cycle = 0;; ++cycle) {
    const Lockstep::Drive& in = lockstep.drive(cycle);
    out.ports["cmd_valid_i"] += cycle > 0 && in.cmd_valid != valid ? 1 : 0;
    out.ports["pix_ready_i"] += cycle > 0 && in.pix_ready != ready ? 1 : 0;
    valid = in.cmd_valid;
    ready = in.pix_ready;
    data.see(in.cmd_data);
    if (in.cmd_valid) std::copy(in.cmd_data, in.cmd_data + unit.port_words, last_beat.begin());
    held.see(last_beat.data());
    const CycleModel::Edge e = dut.clock(in.cmd_valid, in.cmd_data, in.pix_ready);
    const Lockstep::Sample s = activity_ports_impl::sample_of_edge(e);
    const size_t first = next;
    if (e.pix_fire && in.pix_ready) next += static_cast<size_t>(e.pix_count);
    const auto colour = [&](int lsb, int width) {
      return activity_ports_impl::stand_in_colour(pixels, first, unit, lsb, width);
    };
    const bool go_on = lockstep.edge(cycle, s, colour);
    out.run_cycles = cycle + 1;
    if (!go_on) break;
  }
  for (size_t b = 0; b < data.counts().size(); ++b)
    out.ports["cmd_data_i[" + std::to_string(b) + "]"] = data.counts()[b];
  out.ports["rst_ni"] = 0;  // high from cycle 0
  out.idle_noise = data.total() - held.total();
  const CosimResult r = lockstep.result(0);
  if (!r.passed())
    throw std::runtime_error("port_stimulus: the replay mismatched: " + r.first.expected);
  return out;
}

}  // namespace shadesim
