// Seeded, reproducible stimulus shared by the RTL driver/sink and the cycle model: idle gaps
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
  int gap_pct = 0;     // chance (percent) that a command word is preceded by idle cycles
  int max_gap = 1;     // idle cycles are uniform in 1..max_gap
  int stall_pct = 0;   // chance (percent) that pix_ready is low on a cycle

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

// Offers the command words one at a time with the stimulus's idle gaps; valid stays high until
// the word is accepted (valid/ready rule: valid never depends on ready).
class CommandDriver {
 public:
  CommandDriver(const std::vector<uint64_t>& words, const Stimulus& stim)
      : words_(&words), size_(words.size()), stim_(stim), wait_(stim.gap_before(0)) {}

  bool valid() const { return index_ < size_ && wait_ == 0; }
  uint64_t word() const { return index_ < size_ ? (*words_)[index_] : 0; }
  bool done() const { return index_ >= size_; }
  size_t index() const { return index_; }

  // Call once per clock edge with whether the offered word was accepted on it.
  void clock(bool accepted) {
    if (accepted) {
      ++index_;
      wait_ = stim_.gap_before(index_);
    } else if (wait_ > 0) {
      --wait_;
    }
  }

 private:
  const std::vector<uint64_t>* words_;  // not resized while the driver lives
  size_t size_;
  Stimulus stim_;
  size_t index_ = 0;
  int wait_ = 0;
};

}  // namespace shadesim
