// Seeded mutation tests of every input parser: scene JSON (load_scene), mesh files
// (load_mesh_file), the command stream's text form (read_text, config_from_json through its
// header) and binary form (decode). A few thousand deterministic mutants of real inputs - byte
// flips, deletions, truncations, duplicated lines, numbers replaced by huge, negative or
// NaN-like tokens, bit flips in words - must each either load or throw the parser's own error
// type with a message naming the source. Anything else (another exception type, a message that
// does not say where, a value that loads but differs from what the text says, a loaded stream
// the model cannot run) is collected and reported with the seed and mutant number to replay it.
// A crash or a hang fails the test executable itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "host/frame.h"
#include "host/mesh.h"
#include "host/mesh_import.h"
#include "host/reference.h"
#include "host/scene.h"
#include "model/command_stream.h"
#include "model/shade_unit.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

constexpr uint64_t kSeed = 20261121;

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Tokens that break naive number handling: out of range for double, int64, int32, uint16;
// NaN and infinity spellings; signs; forms JSON or istream do not accept; non-numbers.
const std::vector<std::string> kNastyTokens = {"1e308",
                                               "-1e308",
                                               "1e999",
                                               "-1e999",
                                               "NaN",
                                               "nan",
                                               "inf",
                                               "-inf",
                                               "Infinity",
                                               "-1",
                                               "0",
                                               "-0",
                                               "1e-320",
                                               "9223372036854775807",
                                               "9223372036854775808",
                                               "-9223372036854775809",
                                               "18446744073709551616",
                                               "2147483647",
                                               "2147483648",
                                               "-2147483649",
                                               "4294967296",
                                               "4294967297",
                                               "65535",
                                               "65536",
                                               "1.5",
                                               "0x10",
                                               "1e5",
                                               "",
                                               "--1",
                                               "+1",
                                               "007",
                                               "null",
                                               "true",
                                               "\"x\"",
                                               "[]",
                                               "{}",
                                               "|",
                                               "#"};

// Deterministic mutations; every call draws from the one seeded engine, so mutant i of a run is
// reproducible from the seed alone.
class Mutator {
 public:
  explicit Mutator(uint64_t seed) : rng_(seed) {}

  size_t below(size_t n) {
    return n == 0 ? 0 : std::uniform_int_distribution<size_t>(0, n - 1)(rng_);
  }

  // 1 to 3 random text mutations; `what` describes them for the report.
  std::string mutate_text(std::string s, std::string* what) {
    const size_t count = 1 + below(3);
    for (size_t i = 0; i < count; ++i) s = mutate_text_once(s, what);
    return s;
  }

  // Only number-for-token replacements: the structure survives, the values are hostile.
  std::string mutate_values(std::string s, std::string* what) {
    const size_t count = 1 + below(2);
    for (size_t i = 0; i < count; ++i) s = replace_number(s, what);
    return s;
  }

  std::vector<uint64_t> mutate_words(std::vector<uint64_t> w, const std::vector<size_t>& headers,
                                     std::string* what) {
    const size_t count = 1 + below(2);
    for (size_t i = 0; i < count; ++i) w = mutate_words_once(w, headers, what);
    return w;
  }

 private:
  static std::vector<std::pair<size_t, size_t>> lines(const std::string& s) {
    std::vector<std::pair<size_t, size_t>> out;  // [begin, end) including the newline
    size_t begin = 0;
    while (begin < s.size()) {
      size_t end = s.find('\n', begin);
      end = end == std::string::npos ? s.size() : end + 1;
      out.emplace_back(begin, end);
      begin = end;
    }
    return out;
  }

  static std::vector<std::pair<size_t, size_t>> numbers(const std::string& s) {
    std::vector<std::pair<size_t, size_t>> out;  // [begin, end) of -?digits[.digits][e[+-]digits]
    size_t i = 0;
    auto digit = [&](size_t k) { return k < s.size() && s[k] >= '0' && s[k] <= '9'; };
    while (i < s.size()) {
      const bool starts = digit(i) || (s[i] == '-' && digit(i + 1));
      const bool inside_word =
          i > 0 && (std::isalnum(static_cast<unsigned char>(s[i - 1])) || s[i - 1] == '.');
      if (!starts || inside_word) {
        ++i;
        continue;
      }
      size_t j = s[i] == '-' ? i + 1 : i;
      while (digit(j)) ++j;
      if (j < s.size() && s[j] == '.' && digit(j + 1)) {
        ++j;
        while (digit(j)) ++j;
      }
      if (j < s.size() && (s[j] == 'e' || s[j] == 'E')) {
        size_t k = j + 1;
        if (k < s.size() && (s[k] == '+' || s[k] == '-')) ++k;
        if (digit(k)) {
          j = k;
          while (digit(j)) ++j;
        }
      }
      out.emplace_back(i, j);
      i = j;
    }
    return out;
  }

  std::string replace_number(const std::string& s, std::string* what) {
    const auto nums = numbers(s);
    if (nums.empty()) return s;
    const auto [b, e] = nums[below(nums.size())];
    const std::string& token = kNastyTokens[below(kNastyTokens.size())];
    *what += " number@" + std::to_string(b) + "(" + s.substr(b, e - b) + ")->'" + token + "'";
    return s.substr(0, b) + token + s.substr(e);
  }

  std::string mutate_text_once(const std::string& s, std::string* what) {
    if (s.empty()) return s;
    const size_t pos = below(s.size());
    switch (below(10)) {
      case 0: {
        const char c = static_cast<char>(below(256));
        *what +=
            " byte@" + std::to_string(pos) + "=" + std::to_string(static_cast<unsigned char>(c));
        std::string t = s;
        t[pos] = c;
        return t;
      }
      case 1: {
        const int bit = static_cast<int>(below(8));
        *what += " bitflip@" + std::to_string(pos) + "." + std::to_string(bit);
        std::string t = s;
        t[pos] = static_cast<char>(t[pos] ^ (1 << bit));
        return t;
      }
      case 2: {
        const size_t n = 1 + below(8);
        *what += " delete@" + std::to_string(pos) + "+" + std::to_string(n);
        return s.substr(0, pos) + s.substr(std::min(s.size(), pos + n));
      }
      case 3:
        *what += " truncate@" + std::to_string(pos);
        return s.substr(0, pos);
      case 4: {
        const auto ls = lines(s);
        const auto [b, e] = ls[below(ls.size())];
        *what += " dupline@" + std::to_string(b);
        return s.substr(0, e) + s.substr(b, e - b) + s.substr(e);
      }
      case 5: {
        const auto ls = lines(s);
        const auto [b, e] = ls[below(ls.size())];
        *what += " delline@" + std::to_string(b);
        return s.substr(0, b) + s.substr(e);
      }
      case 6: {
        const auto ls = lines(s);
        if (ls.size() < 2) return s;
        const size_t k = below(ls.size() - 1);
        *what += " swaplines@" + std::to_string(ls[k].first);
        const std::string a = s.substr(ls[k].first, ls[k].second - ls[k].first);
        const std::string b = s.substr(ls[k + 1].first, ls[k + 1].second - ls[k + 1].first);
        return s.substr(0, ls[k].first) + b + a + s.substr(ls[k + 1].second);
      }
      case 7:
      case 8:
        return replace_number(s, what);
      default: {
        const std::string& token = kNastyTokens[below(kNastyTokens.size())];
        *what += " insert@" + std::to_string(pos) + "'" + token + "'";
        return s.substr(0, pos) + token + s.substr(pos);
      }
    }
  }

  std::vector<uint64_t> mutate_words_once(std::vector<uint64_t> w,
                                          const std::vector<size_t>& headers, std::string* what) {
    if (w.empty()) return w;
    const size_t pos = below(w.size());
    switch (below(9)) {
      case 0: {
        const int bit = static_cast<int>(below(64));
        *what += " wordbit@" + std::to_string(pos) + "." + std::to_string(bit);
        w[pos] ^= uint64_t{1} << bit;
        return w;
      }
      case 1:
      case 2: {  // header fields: opcode, flags, origin, count
        const size_t h = headers[below(headers.size())];
        if (h >= w.size()) return w;
        const int bit = static_cast<int>(below(64));
        *what += " headerbit@" + std::to_string(h) + "." + std::to_string(bit);
        w[h] ^= uint64_t{1} << bit;
        return w;
      }
      case 3: {
        const size_t h = headers[below(headers.size())];
        if (h >= w.size()) return w;
        const uint64_t count = below(65536);
        *what += " headercount@" + std::to_string(h) + "=" + std::to_string(count);
        w[h] = (w[h] & ~uint64_t{0xFFFF}) | count;
        return w;
      }
      case 4:
        *what += " delword@" + std::to_string(pos);
        w.erase(w.begin() + static_cast<long>(pos));
        return w;
      case 5:
        *what += " dupword@" + std::to_string(pos);
        w.insert(w.begin() + static_cast<long>(pos), w[pos]);
        return w;
      case 6: {
        const uint64_t v = std::uniform_int_distribution<uint64_t>()(rng_);
        *what += " insword@" + std::to_string(pos);
        w.insert(w.begin() + static_cast<long>(pos), v);
        return w;
      }
      case 7:
        *what += " truncwords@" + std::to_string(pos);
        w.resize(pos);
        return w;
      default: {
        const uint64_t extremes[] = {0, ~uint64_t{0}, uint64_t{1} << 63, (uint64_t{1} << 63) - 1};
        const uint64_t v = extremes[below(4)];
        *what += " extremeword@" + std::to_string(pos);
        w[pos] = v;
        return w;
      }
    }
  }

  std::mt19937_64 rng_;
};

// What the mutants did. Problems carry enough to replay: input, mutant number, mutations.
struct Tally {
  size_t loaded = 0, rejected = 0;
  std::vector<std::string> problems;

  void problem(const std::string& input, size_t i, const std::string& what,
               const std::string& message) {
    problems.push_back(input + " mutant " + std::to_string(i) + " [" + what + " ]: " + message);
  }
};

std::string short_message(const std::string& m) {
  return m.size() > 300 ? m.substr(0, 300) + "..." : m;
}

// Runs `load`; the only acceptable exception is `Error` whose message contains `source`.
template <typename Error>
bool loads_or_rejects_cleanly(const std::function<void()>& load, const std::string& source,
                              const std::string& input, size_t i, const std::string& what,
                              Tally& tally) {
  try {
    load();
    ++tally.loaded;
    return true;
  } catch (const Error& e) {
    ++tally.rejected;
    // SHADESIM_MUTATION_VERBOSE=1 prints every rejection, to read the messages a user would get.
    if (std::getenv("SHADESIM_MUTATION_VERBOSE"))
      std::cout << input << " " << i << ": " << e.what() << "\n";
    if (std::string(e.what()).find(source) == std::string::npos) {
      tally.problem(
          input, i, what,
          "message does not name the source '" + source + "': " + short_message(e.what()));
    }
  } catch (const std::exception& e) {
    ++tally.rejected;
    tally.problem(input, i, what,
                  std::string("threw ") + typeid(e).name() + " instead of " + typeid(Error).name() +
                      ": " + short_message(e.what()));
  }
  return false;
}

void expect_no_problems(const char* parser, const Tally& tally) {
  std::cout << parser << ": " << tally.loaded << " mutants loaded, " << tally.rejected
            << " rejected, " << tally.problems.size() << " problem(s) (seed " << kSeed << ")\n";
  EXPECT_TRUE(tally.problems.empty()) << [&] {
    std::string out;
    for (size_t k = 0; k < tally.problems.size() && k < 12; ++k) out += tally.problems[k] + "\n";
    return out;
  }();
  EXPECT_GT(tally.loaded, 0u) << "no mutant loaded: the mutations are all fatal, the test is weak";
  EXPECT_GT(tally.rejected, 0u) << "no mutant was rejected: the parser checks nothing";
}

std::vector<std::string> shipped_scenes() {
  std::vector<std::string> out;
  for (const char* dir : {"/scenes", "/scenes/hard"}) {
    for (const auto& entry : fs::directory_iterator(std::string(SHADESIM_SOURCE_DIR) + dir)) {
      if (entry.path().extension() != ".json") continue;
      out.push_back(entry.path().string());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

bool has_assimp_models() { return fs::exists("/usr/share/assimp/models/BLEND/Suzanne_248.blend"); }

// A private copy of the scene directory's mesh files, so mutants written to the temporary
// directory still find the meshes they name by relative path.
std::string mutant_dir() {
  std::string dir = testing::TempDir() + "shadesim_mutants/";  // returned: moved
  fs::create_directories(dir);
  for (const auto& entry :
       fs::directory_iterator(std::string(SHADESIM_SOURCE_DIR) + "/scenes/hard")) {
    if (entry.path().extension() == ".obj") {
      fs::copy_file(entry.path(), dir + entry.path().filename().string(),
                    fs::copy_options::overwrite_existing);
    }
  }
  return dir;
}

TEST(Mutation, SceneJsonLoadsOrThrowsSceneErrorNamingTheFile) {
  Mutator mutator(kSeed);
  Tally tally;
  const std::string dir = mutant_dir();
  for (const std::string& scene : shipped_scenes()) {
    const bool real_mesh = read_file(scene).find("\"mesh\"") != std::string::npos &&
                           read_file(scene).find("/usr/share/assimp") != std::string::npos;
    if (real_mesh && !has_assimp_models()) continue;
    const std::string text = read_file(scene);
    const std::string path = dir + fs::path(scene).filename().string();
    // Loading a real mesh file costs assimp's time; fewer of those.
    const size_t count = real_mesh ? 40 : 200;
    for (size_t i = 0; i < count; ++i) {
      std::string what;
      write_file(path, mutator.mutate_text(text, &what));
      loads_or_rejects_cleanly<SceneError>([&] { (void)load_scene(path); }, path,
                                           fs::path(scene).filename().string(), i, what, tally);
    }
  }
  expect_no_problems("load_scene", tally);
}

TEST(Mutation, MeshFileLoadsOrThrowsSceneErrorNamingTheFile) {
  Mutator mutator(kSeed + 1);
  Tally tally;
  const std::string dir = mutant_dir();
  const std::string text =
      read_file(std::string(SHADESIM_SOURCE_DIR) + "/scenes/hard/long_span_tri.obj");
  const std::string path = dir + "mutant.obj";
  // One import process for all mutants, as the mesh fuzzer has: load_mesh_file's process per
  // file spent 20 s forking here. An import that crashes or runs away ends that process and the
  // next mutant starts a fresh one, so each mutant is still judged on its own.
  MeshImporter importer;
  for (size_t i = 0; i < 300; ++i) {
    std::string what;
    write_file(path, mutator.mutate_text(text, &what));
    const bool loaded = loads_or_rejects_cleanly<SceneError>(
        [&] {
          const Mesh m = importer.load(path);
          // What loads must be usable: finite positions, unit normals, indices in range.
          for (const Vec3& p : m.positions)
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
              throw std::logic_error("loaded a non-finite position");
          for (const Vec3& n : m.normals)
            if (!(std::fabs(length(n) - 1) < 1e-9))
              throw std::logic_error("loaded a non-unit normal");
          for (const auto& t : m.triangles)
            for (uint32_t k : t)
              if (k >= m.positions.size()) throw std::logic_error("loaded an index out of range");
        },
        path, "long_span_tri.obj", i, what, tally);
    (void)loaded;
  }
  expect_no_problems("load_mesh_file", tally);
}

// Small frames of shipped scenes, one per specular unit and one RGB two-light scene: their
// command streams are the seeds for the stream mutants.
struct SeedStream {
  std::string name;
  CommandStream stream;
};

std::vector<SeedStream> seed_streams() {
  const std::string dir = mutant_dir();
  auto small = [&](const std::string& scene, int w, int h) {
    nlohmann::json j;
    std::ifstream(std::string(SHADESIM_SOURCE_DIR) + "/scenes/" + scene) >> j;
    j["image"] = {{"width", w}, {"height", h}};
    std::string path = dir + "small_" + scene;  // returned: moved
    std::ofstream(path) << j.dump(1);
    return path;
  };
  std::vector<SeedStream> out;
  const std::string spec = small("specular.json", 20, 20);
  for (SpecularUnitKind kind : {SpecularUnitKind::kIdeal, SpecularUnitKind::kLut,
                                SpecularUnitKind::kSchlick, SpecularUnitKind::kWpow}) {
    FrameOptions o;
    o.specular_override = kind;
    if (kind == SpecularUnitKind::kLut) o.base.specular.lut.addr_bits = 6;  // short TABLE lines
    out.push_back({"specular/" + to_string(kind), prepare_frame(spec, o).encoded.stream});
  }
  out.push_back(
      {"multi/rgb", prepare_frame(small("multi.json", 24, 16), FrameOptions{}).encoded.stream});
  return out;
}

std::string to_text(const CommandStream& s) {
  std::ostringstream os;
  s.write_text(os);
  return os.str();
}

// The integers of each command line (header, comments and blank lines skipped), as the text says
// them: what a loaded stream must hold. Integers are maximal runs [+-]?digits, so "120|" or
// "5last" (which the reader accepts as "120 |" and "5 last", harmlessly) say 120 and 5; values
// are kept as long double so out-of-range ones compare unequal.
std::vector<std::vector<long double>> integers_per_command(const std::string& text) {
  std::vector<std::vector<long double>> out;
  std::istringstream in(text);
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream ls(line);
    std::string op;
    if (!(ls >> op)) continue;
    if (header) {
      header = false;
      continue;
    }
    std::string rest;
    std::getline(ls, rest);
    std::vector<long double> ints;
    auto digit = [&](size_t k) { return k < rest.size() && rest[k] >= '0' && rest[k] <= '9'; };
    for (size_t i = 0; i < rest.size();) {
      const bool sign = (rest[i] == '-' || rest[i] == '+') && digit(i + 1);
      if (!sign && !digit(i)) {
        ++i;
        continue;
      }
      size_t j = sign ? i + 1 : i;
      while (digit(j)) ++j;
      ints.push_back(std::strtold(rest.substr(i, j - i).c_str(), nullptr));
      i = j;
    }
    out.push_back(ints);
  }
  return out;
}

// Runs a loaded stream through the model: it must shade or stop with a stream/unit error, never
// crash. Streams whose spans would emit absurdly many pixels are reported, not run.
void run_loaded(const CommandStream& s, const std::string& input, size_t i, const std::string& what,
                Tally& tally) {
  int64_t pixels = 0;
  const int64_t xy_max = (int64_t{1} << s.config.xy_bits) - 1;
  for (const Command& c : s.commands) {
    if (const auto* span = std::get_if<SpanCmd>(&c)) {
      pixels += span->length;
      if (int64_t{span->x0} + span->length - 1 > xy_max) {
        tally.problem(input, i, what,
                      "validated span ends past the screen: x0=" + std::to_string(span->x0) +
                          " length=" + std::to_string(span->length));
        return;
      }
    }
  }
  if (pixels > (int64_t{1} << 22)) return;
  try {
    ShadeUnit unit(s.config);
    (void)unit.run(s);
  } catch (const CommandStreamError&) {
  } catch (const std::invalid_argument&) {
  } catch (const std::exception& e) {
    tally.problem(input, i, what,
                  std::string("model threw ") + typeid(e).name() + ": " + short_message(e.what()));
  }
}

TEST(Mutation, CommandStreamTextLoadsFaithfullyOrThrowsNamingTheSource) {
  Mutator mutator(kSeed + 2);
  Tally tally;
  for (const SeedStream& seed : seed_streams()) {
    const std::string text = to_text(seed.stream);
    std::istringstream unmutated(text);
    ASSERT_EQ(to_text(CommandStream::read_text(unmutated, "seed")), text);
    for (size_t i = 0; i < 500; ++i) {
      std::string what;
      const std::string mutant = mutator.mutate_text(text, &what);
      const std::string source = "mutant-" + std::to_string(i) + ".txt";
      CommandStream loaded;
      const bool ok = loads_or_rejects_cleanly<CommandStreamError>(
          [&] {
            std::istringstream is(mutant);
            loaded = CommandStream::read_text(is, source);
          },
          source, seed.name, i, what, tally);
      if (!ok) continue;
      // What loaded is what the text says: same integers, command by command.
      const auto said = integers_per_command(mutant);
      const auto held = integers_per_command(to_text(loaded));
      if (said != held) {
        std::string diff;
        for (size_t k = 0; k < std::min(said.size(), held.size()); ++k) {
          if (said[k] != held[k]) {
            diff = "command " + std::to_string(k) + ": text says";
            for (auto v : said[k]) diff += " " + std::to_string(static_cast<double>(v));
            diff += ", loaded";
            for (auto v : held[k]) diff += " " + std::to_string(static_cast<double>(v));
            break;
          }
        }
        tally.problem(seed.name, i, what, "loaded values differ from the text: " + diff);
        continue;
      }
      // A loaded stream re-encodes to binary and decodes to the same commands.
      try {
        const CommandStream again =
            CommandStream::decode(loaded.encode(), loaded.config, "<re-encoded>");
        if (to_text(again) != to_text(loaded))
          tally.problem(seed.name, i, what, "binary round trip changed the stream");
      } catch (const std::exception& e) {
        tally.problem(seed.name, i, what,
                      std::string("binary round trip threw: ") + short_message(e.what()));
      }
      run_loaded(loaded, seed.name, i, what, tally);
    }
  }
  expect_no_problems("read_text", tally);
}

// Command-header word indices of an encoded stream.
std::vector<size_t> header_indices(const CommandStream& s) {
  std::vector<size_t> out;
  size_t at = 0;
  for (const Command& c : s.commands) {
    out.push_back(at);
    CommandStream one;
    one.config = s.config;
    one.commands = {c};
    at += one.encode().size();
  }
  return out;
}

TEST(Mutation, CommandStreamBinaryDecodesOrThrowsNamingTheSource) {
  Mutator mutator(kSeed + 3);
  Tally tally;
  for (const SeedStream& seed : seed_streams()) {
    const std::vector<uint64_t> words = seed.stream.encode();
    const std::vector<size_t> headers = header_indices(seed.stream);
    for (size_t i = 0; i < 500; ++i) {
      std::string what;
      const std::vector<uint64_t> mutant = mutator.mutate_words(words, headers, &what);
      CommandStream loaded;
      const bool ok = loads_or_rejects_cleanly<CommandStreamError>(
          [&] { loaded = CommandStream::decode(mutant, seed.stream.config, "<binary>"); },
          "<binary>", seed.name, i, what, tally);
      if (!ok) continue;
      // Decoding is a function of the words: re-encoding and decoding again changes nothing.
      // (Reserved header bits are ignored, so the words themselves need not come back.)
      try {
        const CommandStream again =
            CommandStream::decode(loaded.encode(), loaded.config, "<re-encoded>");
        if (to_text(again) != to_text(loaded))
          tally.problem(seed.name, i, what, "re-encoding changed the stream");
      } catch (const std::exception& e) {
        tally.problem(seed.name, i, what,
                      std::string("re-encoding threw: ") + short_message(e.what()));
      }
      run_loaded(loaded, seed.name, i, what, tally);
    }
  }
  expect_no_problems("decode", tally);
}

// Numeric leaves of `said` (a mutant config) that `held` (config_to_json of what loaded) does not
// hold as the same number (12.9 read as 12, 4294967297 as 1, true as 1), as a problem.
std::string config_mismatch(const nlohmann::json& said, const nlohmann::json& held,
                            const std::string& path) {
  if (said.is_object()) {
    for (const auto& item : said.items()) {
      if (!held.is_object() || !held.contains(item.key())) continue;  // unknown keys are ignored
      // Returned: moved, so not const.
      std::string m = config_mismatch(item.value(), held.at(item.key()), path + "." + item.key());
      if (!m.empty()) return m;
    }
    return "";
  }
  if (!held.is_number()) return "";  // strings are formats and names, checked by their parsers
  if (said.is_number() && said.get<double>() == held.get<double>()) return "";
  return path + ": text says " + said.dump() + ", loaded " + held.dump();
}

TEST(Mutation, StreamHeaderConfigLoadsFaithfullyOrThrowsNamingTheSource) {
  Mutator mutator(kSeed + 4);
  Tally tally;
  for (const SeedStream& seed : seed_streams()) {
    const std::string json = config_to_json(seed.stream.config);
    for (size_t i = 0; i < 300; ++i) {
      std::string what;
      const std::string mutant = mutator.mutate_text(json, &what);
      const std::string source = "config-mutant-" + std::to_string(i) + ": ";
      UnitConfig loaded;
      if (!loads_or_rejects_cleanly<CommandStreamError>(
              [&] { loaded = config_from_json(mutant, source); }, source, seed.name, i, what,
              tally))
        continue;
      const std::string m = config_mismatch(
          nlohmann::json::parse(mutant), nlohmann::json::parse(config_to_json(loaded)), "config");
      if (!m.empty())
        tally.problem(seed.name, i, what, "loaded config differs from the text: " + m);
    }
  }
  expect_no_problems("config_from_json", tally);
}

// Beyond the parser: hostile values that a scene file may legally hold (huge, tiny, negative
// where allowed) must not crash the host pipeline or produce a stream that fails validation.
TEST(Mutation, SceneValuesThatLoadGoThroughThePipelineOrThrowDocumentedErrors) {
  Mutator mutator(kSeed + 5);
  Tally tally;
  const std::string dir = mutant_dir();
  for (const std::string& scene : shipped_scenes()) {
    if (read_file(scene).find("/usr/share/assimp") != std::string::npos) continue;  // slow to load
    nlohmann::json j;
    std::ifstream(scene) >> j;
    j["image"] = {{"width", 40}, {"height", 24}};  // small: every mutant is rendered
    const std::string text = j.dump(1);
    const std::string path = dir + "pipeline_" + fs::path(scene).filename().string();
    for (size_t i = 0; i < 40; ++i) {
      std::string what;
      write_file(path, mutator.mutate_values(text, &what));
      const std::string name = fs::path(scene).filename().string();
      try {
        (void)load_scene(path);
      } catch (const std::exception&) {
        continue;  // the parser tests cover rejection
      }
      try {
        FrameOptions o;
        o.max_depth = 8;  // a mutated budget may ask for endless subdivision
        const PreparedFrame f = prepare_frame(path, o);
        ShadeUnit unit(f.config);
        const auto pixels = unit.run(f.encoded.stream);
        const auto ref =
            render_reference(f.setup.triangles, f.visibility, f.scene, f.config.channels);
        for (double v : ref.values)
          if (!(v >= 0 && v <= 1))
            throw std::logic_error("reference value outside [0, 1]: " + std::to_string(v));
        ++tally.loaded;
        (void)pixels;
      } catch (const SceneError&) {
        ++tally.rejected;
      } catch (const std::invalid_argument&) {
        ++tally.rejected;
      } catch (const std::exception& e) {
        ++tally.rejected;
        tally.problem(
            name, i, what,
            std::string("pipeline threw ") + typeid(e).name() + ": " + short_message(e.what()));
      }
    }
  }
  std::cout << "pipeline: " << tally.loaded << " mutants rendered, " << tally.rejected
            << " rejected with a documented error, " << tally.problems.size() << " problem(s)\n";
  EXPECT_TRUE(tally.problems.empty()) << [&] {
    std::string out;
    for (size_t k = 0; k < tally.problems.size() && k < 12; ++k) out += tally.problems[k] + "\n";
    return out;
  }();
  EXPECT_GT(tally.loaded, 20u) << "too few value mutants survive loading to exercise the pipeline";
}

// Regressions for defects the mutants found in CommandStream::read_text and config_from_json
// (32-bit truncation of integers, int overflow in the span check, get<int>() of non-integers).
CommandStream read_one_line(const std::string& line) {
  std::istringstream is("shadesim-commands 2 " + config_to_json(UnitConfig{}) + "\n" + line + "\n");
  return CommandStream::read_text(is, "repro.txt");
}

TEST(Mutation, TextReaderRejectsIntegersThatDoNotFitTheirField) {
  // Each read into 32 bits would load as its truncation: x0 0, y 0, length 1, xo 1, table base 0.
  for (const char* line :
       {"span 0 4294967296 5", "span 4294967296 0 5", "span 0 0 4294967297",
        "tri 4294967297 0 | 0 0 0 0 0 0 | 0 0 0 0 0 0", "table 4294967296 1 2"}) {
    EXPECT_THROW(read_one_line(line), CommandStreamError) << line;
  }
}

TEST(Mutation, ConfigHeaderRejectsNumbersThatAreNotInts) {
  // Widths read with get<int>() would load these as 1, 12, 1.
  const std::string json = config_to_json(UnitConfig{});
  auto with = [&](const std::string& from, const std::string& to) {
    std::string t = json;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  for (const std::string& bad :
       {with("\"channels\":1", "\"channels\":4294967297"),
        with("\"xy_bits\":12", "\"xy_bits\":12.9"), with("\"out_bits\":8", "\"out_bits\":true")}) {
    EXPECT_THROW(config_from_json(bad, "repro: "), CommandStreamError) << bad;
  }
}

TEST(Mutation, TextReaderRejectsASpanPastTheScreenWhateverItsLength) {
  // x0 + length - 1 > xy_max tested in int32 overflows at 100 + 2147483647 (undefined
  // behaviour): the span would validate and the model shade 2^31 pixels.
  EXPECT_THROW(read_one_line("span 0 100 2147483647"), CommandStreamError);
}

}  // namespace
}  // namespace shadesim
