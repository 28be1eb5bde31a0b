// Testbench stimulus, seeded and reproducible, shared by the RTL driver/sink and the cycle model
// (sim/harness/cycle_run.h): idle gaps
// before each command word and back-pressure on the pixel port. Both are pure functions of the
// seed and of a word index or a cycle number, so the RTL and the cycle model see the identical
// pattern as long as they accept the same words on the same cycles (which is what is checked).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace shadesim {

constexpr uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

struct Stimulus {
  uint64_t seed = 1;
  int gap_pct = 0;    // chance (percent) that a command word is preceded by idle cycles
  int max_gap = 1;    // idle cycles are uniform in 1..max_gap
  int stall_pct = 0;  // chance (percent) that pix_ready is low on a cycle

  // Idle cycles before word `index` is offered (after word index-1 was accepted).
  int gap_before(size_t index) const {
    if (gap_pct <= 0 || max_gap <= 0) return 0;
    const uint64_t h = splitmix64(seed * 0x2545F4914F6CDD1Dull + 2 * index + 1);
    if (static_cast<int>(h % 100) >= gap_pct) return 0;
    return 1 + static_cast<int>((h >> 32) % static_cast<uint64_t>(max_gap));
  }

  bool pix_ready(uint64_t cycle) const {
    if (stall_pct <= 0) return true;
    const uint64_t h = splitmix64((seed ^ 0xA5A5A5A5DEADBEEFull) * 0x9E3779B97F4A7C15ull + cycle);
    return static_cast<int>(h % 100) >= stall_pct;
  }

  // Command-line form, for replay lines.
  std::string to_args() const {
    return "--seed " + std::to_string(seed) + " --gap-pct " + std::to_string(gap_pct) +
           " --max-gap " + std::to_string(max_gap) + " --stall-pct " + std::to_string(stall_pct);
  }
};

// Offers the command words a beat at a time (port_words consecutive words, the last beat padded
// with zero words: model/command_stream.h) with the stimulus's idle gaps before each beat; valid
// stays high until the beat is accepted (valid/ready rule: valid never depends on ready).
class CommandDriver {
 public:
  CommandDriver(const std::vector<uint64_t>& words, const Stimulus& stim, int port_words = 1)
      : words_(&words),
        port_words_(static_cast<size_t>(port_words)),
        beats_((words.size() + port_words_ - 1) / port_words_),
        stim_(stim),
        wait_(stim.gap_before(0)) {
    // The last beat, padded, kept apart so that beat() is always port_words readable words.
    last_beat_.assign(port_words_, 0);
    if (beats_ > 0) {
      for (size_t i = (beats_ - 1) * port_words_; i < words.size(); ++i)
        last_beat_[i % port_words_] = words[i];
    }
  }

  bool valid() const { return index_ < beats_ && wait_ == 0; }
  // The beat on the port: port_words words (zeros after the end).
  const uint64_t* beat() const {
    if (index_ + 1 < beats_) return words_->data() + index_ * port_words_;
    return index_ + 1 == beats_ ? last_beat_.data() : zero_beat();
  }
  uint64_t word() const { return beat()[0]; }  // a one-word port's beat
  bool done() const { return index_ >= beats_; }
  size_t index() const { return index_; }  // beats accepted so far
  int port_words() const { return static_cast<int>(port_words_); }

  // Call once per clock edge with whether the offered beat was accepted on it.
  void clock(bool accepted) {
    if (accepted) {
      ++index_;
      wait_ = stim_.gap_before(index_);
    } else if (wait_ > 0) {
      --wait_;
    }
  }

 private:
  static const uint64_t* zero_beat() {
    static constexpr uint64_t kZeros[8] = {};
    return kZeros;
  }

  const std::vector<uint64_t>* words_;  // not resized while the driver lives
  size_t port_words_;
  size_t beats_;
  Stimulus stim_;
  std::vector<uint64_t> last_beat_;
  size_t index_ = 0;
  int wait_ = 0;
};

}  // namespace shadesim
