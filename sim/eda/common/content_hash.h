// Content hashes for cache keys (the RTL build cache, the Yosys area cache): xxHash's XXH3, 128
// bits, over fields that are kept apart (("ab", "c") and ("a", "bc") differ). A cache key, not a
// security boundary.
#pragma once

// Header-only: no library to link.
#define XXH_INLINE_ALL
#include <xxhash.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace shadesim {

class ContentHash {
 public:
  ContentHash() { XXH3_128bits_reset(&state_); }
  // One field: its length, then its bytes.
  ContentHash& add(std::string_view field) {
    const uint64_t n = field.size();
    XXH3_128bits_update(&state_, &n, sizeof n);
    XXH3_128bits_update(&state_, field.data(), field.size());
    return *this;
  }
  // 32 hex digits.
  std::string hex() const {
    const XXH128_hash_t h = XXH3_128bits_digest(&state_);
    char buf[33];
    std::snprintf(buf, sizeof buf, "%016llx%016llx", static_cast<unsigned long long>(h.high64),
                  static_cast<unsigned long long>(h.low64));
    return buf;
  }

 private:
  XXH3_state_t state_;
};

}  // namespace shadesim
