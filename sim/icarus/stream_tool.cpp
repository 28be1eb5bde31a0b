// icarus_stream_tool: the files the Icarus testbench (sim/icarus/tb_shade_unit.sv) reads and
// the check of what it writes.
//
//   icarus_stream_tool export STREAM.cmds --hex WORDS.hex --pixels EXPECTED.txt
//       the stream's binary words for $readmemh (a first line "// shadesim-words N ...", then
//       one 16-digit hex word per line) and the
//       bit-accurate model's pixels (ShadeUnit), one "x y c0 [c1 c2] eor" line each, decimal;
//   icarus_stream_tool random --rtl-config SPEC --scenario mixed --seed 1 --save OUT.cmds
//       a co-simulation random stream (sim/harness/random_stream.h) for an RTL configuration
//       given as cmake/rtl.cmake's entry fields, comma-separated;
//   icarus_stream_tool compare EXPECTED.txt GOT.txt
//       bit-for-bit comparison of two pixel files; the first difference is described.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/command_stream.h"
#include "model/shade_unit.h"
#include "sim/harness/random_stream.h"
#include "sim/harness/rtl_config.h"

namespace shadesim {
namespace {

class ToolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::ofstream open_out(const std::string& path) {
  std::ofstream os(path);
  if (!os) throw ToolError(path + ": cannot open for writing");
  return os;
}

void export_stream(const std::string& stream_path, const std::string& hex_path,
                   const std::string& pixels_path) {
  const CommandStream stream = CommandStream::load(stream_path);
  stream.validate(stream_path);
  if (!hex_path.empty()) {
    std::ofstream os = open_out(hex_path);
    // $readmemh skips // comments; the testbench reads the count from this first line.
    const std::vector<uint64_t> words = stream.encode();
    os << "// shadesim-words " << words.size() << ' ' << stream_path << ": " << stream.config.to_string() << '\n';
    char word[20];
    for (uint64_t w : words) {
      std::snprintf(word, sizeof word, "%016llx\n", static_cast<unsigned long long>(w));
      os << word;
    }
    if (!os) throw ToolError(hex_path + ": write failed");
  }
  if (!pixels_path.empty()) {
    std::ofstream os = open_out(pixels_path);
    ShadeUnit unit(stream.config);
    for (const PixelOut& p : unit.run(stream)) {
      os << p.x << ' ' << p.y;
      for (int c = 0; c < stream.config.channels; ++c) os << ' ' << p.colour[c];
      os << ' ' << (p.end_of_row ? 1 : 0) << '\n';
    }
    if (!os) throw ToolError(pixels_path + ": write failed");
  }
}

// SPEC: name,channels,lights,xy_bits,coef,series,spec_colour,out_bits,specular,spec_out
//       [,fault_lsb_row,fault_stall_row[,port_words,tri_queue]] - the fields of rtl_config() in cmake/rtl.cmake.
RtlConfig parse_rtl_config(const std::string& spec) {
  std::vector<std::string> f;
  std::stringstream ss(spec);
  for (std::string item; std::getline(ss, item, ',');) {
    const auto b = item.find_first_not_of(" \"");
    const auto e = item.find_last_not_of(" \"");
    f.push_back(b == std::string::npos ? "" : item.substr(b, e - b + 1));
  }
  if (f.size() != 10 && f.size() != 12 && f.size() != 14) {
    throw ToolError("--rtl-config '" + spec + "': expected 10, 12 or 14 comma-separated fields "
                    "(name,channels,lights,xy_bits,coef,series,spec_colour,out_bits,specular,"
                    "spec_out[,fault_lsb_row,fault_stall_row[,port_words,tri_queue]]), got " + std::to_string(f.size()));
  }
  auto integer = [&](size_t i, const char* field) {
    try {
      size_t used = 0;
      const int v = std::stoi(f[i], &used);
      if (used == f[i].size()) return v;
    } catch (const std::logic_error&) {
    }
    throw ToolError("--rtl-config field " + std::to_string(i + 1) + " (" + field + "): expected an integer, got '" + f[i] + "'");
  };
  try {
    return make_rtl_config(f[0], integer(1, "channels"), integer(2, "lights"), integer(3, "xy_bits"), f[4], f[5],
                           f[6], integer(7, "out_bits"), f[8], f[9], f.size() >= 12 ? integer(10, "fault_lsb_row") : -1,
                           f.size() >= 12 ? integer(11, "fault_stall_row") : -1, "",
                           f.size() == 14 ? integer(12, "port_words") : 1,
                           f.size() == 14 ? integer(13, "tri_queue") : 1);
  } catch (const std::invalid_argument& e) {
    throw ToolError(std::string("--rtl-config: ") + e.what());
  }
}

void random_to_file(const std::string& spec, const std::string& scenario, uint64_t seed,
                    const std::string& out) {
  const RtlConfig rtl = parse_rtl_config(spec);
  const Scenario sc = scenario_by_name(scenario);
  random_stream(rtl.unit, sc.shape, seed).save(out);
}

std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream is(path);
  if (!is) throw ToolError(path + ": cannot open");
  std::vector<std::string> lines;
  for (std::string line; std::getline(is, line);) lines.push_back(line);
  return lines;
}

// Exit status 0 when identical; otherwise the first difference goes to stderr.
int compare_pixels(const std::string& expected_path, const std::string& got_path) {
  const std::vector<std::string> expected = read_lines(expected_path);
  const std::vector<std::string> got = read_lines(got_path);
  const size_t n = std::min(expected.size(), got.size());
  for (size_t i = 0; i < n; ++i) {
    if (expected[i] != got[i]) {
      std::cerr << "pixel " << i << " (line " << i + 1 << "): expected \"" << expected[i] << "\" ("
                << expected_path << "), got \"" << got[i] << "\" (" << got_path << ")  [x y colour.. eor]\n";
      return 1;
    }
  }
  if (expected.size() != got.size()) {
    std::cerr << "pixel count: expected " << expected.size() << " (" << expected_path << "), got "
              << got.size() << " (" << got_path << "); the first " << n << " agree\n";
    return 1;
  }
  std::cout << "pixels identical: " << n << " (" << got_path << " = " << expected_path << ")\n";
  return 0;
}

int tool_main(int argc, char** argv) {
  CLI::App app{"Command-stream files for the Icarus testbench, and the check of its pixels"};
  app.require_subcommand(1);

  std::string stream_path, hex_path, pixels_path;
  CLI::App* exp = app.add_subcommand("export", "hex words and the model's expected pixels of a saved stream");
  exp->add_option("stream", stream_path, "saved command stream (text form)")->required()->check(CLI::ExistingFile);
  exp->add_option("--hex", hex_path, "write the binary words for $readmemh");
  exp->add_option("--pixels", pixels_path, "write the bit-accurate model's pixels");

  std::string spec, scenario = "mixed", save_path;
  uint64_t seed = 1;
  CLI::App* rnd = app.add_subcommand("random", "save a co-simulation random stream");
  rnd->add_option("--rtl-config", spec, "name,channels,lights,xy_bits,coef,series,spec_colour,out_bits,specular,spec_out")->required();
  rnd->add_option("--scenario", scenario, "mixed, long, short, slow, maxbp, switch")->capture_default_str();
  rnd->add_option("--seed", seed, "stream seed")->capture_default_str();
  rnd->add_option("--save", save_path, "output stream (text form)")->required();

  std::string expected_path, got_path;
  CLI::App* cmp = app.add_subcommand("compare", "compare two pixel files bit for bit");
  cmp->add_option("expected", expected_path, "expected pixels (export --pixels)")->required();
  cmp->add_option("got", got_path, "pixels written by the testbench")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (*exp) {
    if (hex_path.empty() && pixels_path.empty()) throw ToolError("export: give --hex and/or --pixels");
    export_stream(stream_path, hex_path, pixels_path);
    return 0;
  }
  if (*rnd) {
    random_to_file(spec, scenario, seed, save_path);
    return 0;
  }
  return compare_pixels(expected_path, got_path);
}

}  // namespace
}  // namespace shadesim

int main(int argc, char** argv) {
  try {
    return shadesim::tool_main(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "icarus_stream_tool: error: " << e.what() << '\n';
    return 2;
  }
}
