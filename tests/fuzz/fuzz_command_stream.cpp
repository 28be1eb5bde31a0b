// libFuzzer target: the command-stream readers (model/command_stream.h), text and binary.
// The first input byte picks the form: even = text (the rest is a saved stream), odd = binary
// (the rest is little-endian 64-bit words, decoded for one of the configurations below).
// Every input must decode or throw CommandStreamError with a message; a stream that decodes
// must validate, and re-encode to as many words that decode to the same stream (binary), or
// re-read to the same stream (text).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <vector>

#include "model/command_stream.h"
#include "model/unit_config_file.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

using shadesim::CommandStream;
using shadesim::CommandStreamError;
using shadesim::UnitConfig;

// Configurations whose decoders differ: payload sizes follow channels, lights and the specular
// unit's series and parameters.
const std::vector<UnitConfig>& binary_configs() {
  static const std::vector<UnitConfig> configs = [] {
    const char* units[] = {
        "{}",
        R"({"channels": 3, "lights": 2, "specular": {"kind": "lut", "out": "u1.16:sat",
            "lut": {"addr_bits": 10, "entry_bits": 8}}})",
        R"({"channels": 3, "lights": 2, "specular": {"kind": "schlick", "out": "u1.16:sat",
            "schlick": {"quotient_bits": 16, "operand_bits": 24, "timing": "iterative"}}})",
        R"({"channels": 1, "lights": 1, "xy_bits": 11, "series": "s3.20:rnd:sat",
            "specular": {"kind": "wpow", "out": "u1.12:sat",
            "wpow": {"max_m": 16, "base_bits": 16, "timing": "pipelined"}}})",
        R"({"channels": 3, "lights": 1, "port_words": 4, "tri_queue": 2})",
    };
    std::vector<UnitConfig> out;
    for (const char* unit : units) out.push_back(shadesim::overlay_unit_config(unit, {}, "fuzz"));
    return out;
  }();
  return configs;
}

void fuzz_binary(const UnitConfig& config, const uint8_t* data, size_t size) {
  std::vector<uint64_t> words(size / 8);
  if (!words.empty()) std::memcpy(words.data(), data, words.size() * 8);
  try {
    const CommandStream stream = CommandStream::decode(words, config, "<binary>");
    stream.validate("<decoded>");
    // Header bits outside the documented fields are ignored (and encode writes them 0), so the
    // re-encoded stream has the same words in number and must decode to itself.
    const std::vector<uint64_t> encoded = stream.encode();
    if (encoded.size() != words.size())
      shadesim::fuzz::fail("decode then encode changed the length");
    if (CommandStream::decode(encoded, config, "<re-encoded>").encode() != encoded) {
      shadesim::fuzz::fail("decode of the re-encoded stream differs");
    }
  } catch (const CommandStreamError& e) {
    shadesim::fuzz::require_message(e);
  }
}

void fuzz_text(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const CommandStream stream = CommandStream::read_text(in, "<text>");
    stream.validate("<read>");
    std::ostringstream text;
    stream.write_text(text);
    std::istringstream again(text.str());
    const CommandStream reread = CommandStream::read_text(again, "<written>");
    if (reread.encode() != stream.encode()) {
      shadesim::fuzz::fail("write_text then read_text changed the stream");
    }
  } catch (const CommandStreamError& e) {
    shadesim::fuzz::require_message(e);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const uint8_t mode = data[0];
  if (mode % 2 == 0) {
    fuzz_text(data + 1, size - 1);
  } else {
    const auto& configs = binary_configs();
    fuzz_binary(configs[(mode / 2) % configs.size()], data + 1, size - 1);
  }
  return 0;
}
