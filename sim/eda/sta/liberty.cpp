#include "sim/eda/sta/liberty.h"

#include <algorithm>
#include <cctype>
#include <limits>
#include <set>
#include <stdexcept>
#include <utility>

#include "model/text_file.h"

namespace shadesim {
namespace {

// ---- tokens ------------------------------------------------------------------------------------

struct LibToken {
  enum Kind { kWord, kString, kPunct, kEnd } kind = kEnd;
  std::string text;
  int line = 0;
};

// Liberty's lexical level: words (names, numbers), "strings", the punctuation ( ) { } : ; , and
// comments (/* */, //) and backslash line continuations, which are skipped.
class LibLexer {
 public:
  LibLexer(const std::string& text, const std::string& path) : s_(text), path_(path) {}

  LibToken next() {
    if (pending_.kind != LibToken::kEnd) return std::exchange(pending_, LibToken{});
    skip_space();
    LibToken t;
    t.line = line_;
    if (i_ >= s_.size()) return t;
    const char c = s_[i_];
    if (c == '"') {
      t.kind = LibToken::kString;
      for (++i_; i_ < s_.size() && s_[i_] != '"'; ++i_) {
        if (s_[i_] == '\\' && i_ + 1 < s_.size()) ++i_;  // an escaped character or newline
        if (s_[i_] == '\n') ++line_;
        if (s_[i_] != '\n' && s_[i_] != '\r') t.text += s_[i_];
      }
      if (i_ >= s_.size()) fail(t.line, "a string that does not end");
      ++i_;
    } else if (std::string("(){}:;,").find(c) != std::string::npos) {
      t.kind = LibToken::kPunct;
      t.text = std::string(1, c);
      ++i_;
    } else {
      t.kind = LibToken::kWord;
      while (i_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[i_])) &&
             std::string("(){}:;,\"").find(s_[i_]) == std::string::npos && !comment_at(i_))
        t.text += s_[i_++];
    }
    return t;
  }

  // Gives a token back: the next next() returns it.
  void unget(const LibToken& t) { pending_ = t; }

  [[noreturn]] void fail(int line, const std::string& what) const {
    throw std::runtime_error(path_ + ":" + std::to_string(line) +
                             ": not a Liberty library: " + what);
  }

 private:
  bool comment_at(size_t i) const {
    return i + 1 < s_.size() && s_[i] == '/' && (s_[i + 1] == '*' || s_[i + 1] == '/');
  }
  void skip_space() {
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (c == '\n') {
        ++line_;
        ++i_;
      } else if (std::isspace(static_cast<unsigned char>(c)) || c == '\\') {
        ++i_;  // a backslash outside a string continues the line
      } else if (comment_at(i_) && s_[i_ + 1] == '*') {
        const size_t end = s_.find("*/", i_ + 2);
        if (end == std::string::npos) fail(line_, "a comment that does not end");
        line_ += static_cast<int>(std::count(s_.begin() + static_cast<long>(i_),
                                             s_.begin() + static_cast<long>(end), '\n'));
        i_ = end + 2;
      } else if (comment_at(i_)) {
        while (i_ < s_.size() && s_[i_] != '\n') ++i_;
      } else {
        break;
      }
    }
  }

  const std::string& s_;
  std::string path_;
  size_t i_ = 0;
  int line_ = 1;
  LibToken pending_;
};

// ---- statements --------------------------------------------------------------------------------

// Groups whose contents the flow reads; every other group (timing, power, tables) is skipped.
bool liberty_kept_group(const std::string& kind) {
  static const std::set<std::string> kept = {"library", "cell",  "pin",     "bus",       "bundle",
                                             "ff",      "latch", "ff_bank", "latch_bank"};
  return kept.count(kind) > 0;
}

double liberty_number(const std::string& text) {
  try {
    return std::stod(text);
  } catch (const std::exception&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

class LibParser {
 public:
  LibParser(const std::string& text, const std::string& path) : lex_(text, path) {
    lib_.path = path;
  }

  LibertyLibrary parse() {
    LibToken t = lex_.next();
    if (t.kind != LibToken::kWord || t.text != "library")
      lex_.fail(t.line, "expected `library (NAME) {`, found '" + t.text + "'");
    const std::vector<std::string> args = group_args();
    lib_.name = args.empty() ? "" : args[0];
    expect("{");
    body("library", nullptr, nullptr);
    if (lib_.cells.empty()) lex_.fail(t.line, "no cell groups");
    return std::move(lib_);
  }

 private:
  // After a group's name: "( a, b )".
  std::vector<std::string> group_args() {
    expect("(");
    std::vector<std::string> args;
    for (LibToken t = lex_.next(); t.text != ")" || t.kind != LibToken::kPunct; t = lex_.next()) {
      if (t.kind == LibToken::kEnd) lex_.fail(t.line, "a '(' without ')'");
      if (t.kind != LibToken::kPunct) args.push_back(t.text);
    }
    return args;
  }

  void expect(const char* punct) {
    const LibToken t = lex_.next();
    if (t.kind != LibToken::kPunct || t.text != punct)
      lex_.fail(t.line, std::string("expected '") + punct + "', found '" + t.text + "'");
  }

  // Skips a group's body (after its '{') to its '}'.
  void skip_body() {
    for (int depth = 1; depth > 0;) {
      const LibToken t = lex_.next();
      if (t.kind == LibToken::kEnd) lex_.fail(t.line, "a '{' without '}'");
      if (t.kind == LibToken::kPunct) depth += t.text == "{" ? 1 : t.text == "}" ? -1 : 0;
    }
  }

  // A group's statements up to its '}'. `cell` is set inside a cell, `pins` inside its pins.
  void body(const std::string& kind, LibertyCell* cell, std::vector<LibertyPin>* pins);
  void group(const std::string& kind, const std::vector<std::string>& args, LibertyCell* cell);
  void attribute(const std::string& kind, const std::string& name, const std::string& value,
                 LibertyCell* cell, std::vector<LibertyPin>* pins);

  LibLexer lex_;
  LibertyLibrary lib_;
};

void LibParser::body(const std::string& kind, LibertyCell* cell, std::vector<LibertyPin>* pins) {
  for (;;) {
    const LibToken name = lex_.next();
    if (name.kind == LibToken::kPunct && name.text == "}") return;
    if (name.kind == LibToken::kPunct && name.text == ";") continue;
    if (name.kind == LibToken::kEnd) lex_.fail(name.line, "the " + kind + " group does not end");
    if (name.kind != LibToken::kWord) lex_.fail(name.line, "unexpected '" + name.text + "'");
    const LibToken sep = lex_.next();
    if (sep.kind == LibToken::kPunct && sep.text == ":") {
      const LibToken value = lex_.next();
      attribute(kind, name.text, value.text, cell, pins);
      continue;
    }
    if (sep.kind != LibToken::kPunct || sep.text != "(")
      lex_.fail(sep.line, "expected ':' or '(' after '" + name.text + "'");
    std::vector<std::string> args;
    for (LibToken t = lex_.next(); t.text != ")" || t.kind != LibToken::kPunct; t = lex_.next()) {
      if (t.kind == LibToken::kEnd) lex_.fail(t.line, "a '(' without ')'");
      if (t.kind != LibToken::kPunct) args.push_back(t.text);
    }
    const LibToken after = lex_.next();
    if (after.kind == LibToken::kPunct && after.text == "{") {
      if (liberty_kept_group(name.text))
        group(name.text, args, cell);
      else
        skip_body();
    } else if (after.kind != LibToken::kPunct || after.text != ";") {
      lex_.unget(after);  // a complex attribute without its ';'
    }
  }
}

void LibParser::group(const std::string& kind, const std::vector<std::string>& args,
                      LibertyCell* cell) {
  if (kind == "cell") {
    LibertyCell c;
    c.name = args.empty() ? "" : args[0];
    body(kind, &c, &c.pins);
    lib_.cells[c.name] = std::move(c);
  } else if ((kind == "pin" || kind == "bus" || kind == "bundle") && cell) {
    // One group may declare several pins: pin (A, B) { ... }.
    std::vector<LibertyPin> declared;
    body("pin", cell, &declared);
    LibertyPin merged;
    for (const auto& p : declared) merged = p;  // the attributes, collected into one
    for (const auto& n : args) {
      LibertyPin p = merged;
      p.name = n;
      cell->pins.push_back(p);
    }
  } else if (cell) {  // ff, latch, ff_bank, latch_bank
    cell->sequential = true;
    cell->latch = kind.rfind("latch", 0) == 0;
    cell->state_vars = args;
    body(kind, cell, nullptr);
  } else {
    skip_body();
  }
}

void LibParser::attribute(const std::string& kind, const std::string& name,
                          const std::string& value, LibertyCell* cell,
                          std::vector<LibertyPin>* pins) {
  if (kind == "cell" && cell && name == "area") cell->area = liberty_number(value);
  if (kind == "cell" && cell && name == "dont_use") cell->dont_use = value == "true";
  if ((kind == "ff" || kind == "latch" || kind == "ff_bank" || kind == "latch_bank") && cell)
    cell->state[name] = value;
  if (kind != "pin" || !pins) return;
  if (pins->empty()) pins->emplace_back();
  LibertyPin& p = pins->back();
  if (name == "direction") p.direction = value;
  if (name == "function") p.function = value;
  if (name == "clock") p.clock = value == "true";
  if (name == "capacitance") p.capacitance = liberty_number(value);
  if (name == "max_capacitance") p.max_capacitance = liberty_number(value);
}

// ---- functions ---------------------------------------------------------------------------------

// Liberty's Boolean expressions, by precedence from the tightest: ! (prefix) and ' (postfix),
// ^, AND (& * or juxtaposition), OR (| +).
class FunctionEval {
 public:
  FunctionEval(const std::string& text, const std::map<std::string, bool>& inputs)
      : s_(text), in_(inputs) {}

  bool run() {
    const bool v = parse_or();
    skip();
    if (i_ != s_.size()) fail("unexpected '" + s_.substr(i_, 1) + "'");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::invalid_argument("Liberty function \"" + s_ + "\": " + what);
  }
  void skip() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  char peek() {
    skip();
    return i_ < s_.size() ? s_[i_] : '\0';
  }
  static bool name_char(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '[' || c == ']' ||
           c == '.';
  }
  bool starts_operand() {
    const char c = peek();
    return c == '(' || c == '!' || name_char(c);
  }
  bool parse_or() {
    bool v = parse_and();
    while (peek() == '|' || peek() == '+') {
      ++i_;
      v = parse_and() || v;
    }
    return v;
  }
  bool parse_and() {
    bool v = parse_xor();
    for (;;) {
      if (peek() == '&' || peek() == '*') {
        ++i_;
      } else if (!starts_operand()) {
        return v;
      }
      v = parse_xor() && v;
    }
  }
  bool parse_xor() {
    bool v = parse_unary();
    while (peek() == '^') {
      ++i_;
      v = parse_unary() != v;
    }
    return v;
  }
  bool parse_unary() {
    if (peek() == '!') {
      ++i_;
      return !parse_unary();
    }
    bool v = parse_primary();
    while (peek() == '\'') {
      ++i_;
      v = !v;
    }
    return v;
  }
  bool parse_primary() {
    const char c = peek();
    if (c == '(') {
      ++i_;
      const bool v = parse_or();
      if (peek() != ')') fail("a '(' without ')'");
      ++i_;
      return v;
    }
    std::string name;
    while (i_ < s_.size() && name_char(s_[i_])) name += s_[i_++];
    if (name.empty()) fail(c ? std::string("unexpected '") + c + "'" : "it ends too early");
    if (name == "0" || name == "1") return name == "1";
    const auto it = in_.find(name);
    if (it == in_.end()) fail("no value for '" + name + "'");
    return it->second;
  }

  const std::string& s_;
  const std::map<std::string, bool>& in_;
  size_t i_ = 0;
};

// Whether `out` of `cell` computes_function `want` of its inputs (in pin order) on every input
// vector.
template <typename F>
bool computes_function(const LibertyCell& cell, const LibertyPin& out, F want) {
  const auto ins = cell.inputs();
  if (ins.size() > 6 || out.function.empty()) return false;
  for (unsigned v = 0; v < (1u << ins.size()); ++v) {
    std::map<std::string, bool> values;
    std::vector<bool> bits;
    for (size_t k = 0; k < ins.size(); ++k) {
      values[ins[k]->name] = (v >> k) & 1u;
      bits.push_back((v >> k) & 1u);
    }
    try {
      if (eval_liberty_function(out.function, values) != want(bits)) return false;
    } catch (const std::invalid_argument&) {
      return false;  // a function of something other than its inputs (a state, a tri-state)
    }
  }
  return true;
}

// The usable combinational cells with `n_in` inputs and one output.
std::vector<const LibertyCell*> liberty_logic_cells(const LibertyLibrary& lib, size_t n_in) {
  std::vector<const LibertyCell*> out;
  for (const auto& [name, c] : lib.cells) {
    if (!c.sequential && !c.dont_use && c.inputs().size() == n_in && c.outputs().size() == 1)
      out.push_back(&c);
  }
  return out;
}

}  // namespace

const LibertyPin* LibertyCell::pin(const std::string& n) const {
  for (const auto& p : pins)
    if (p.name == n) return &p;
  return nullptr;
}

std::vector<const LibertyPin*> LibertyCell::inputs() const {
  std::vector<const LibertyPin*> out;
  for (const auto& p : pins)
    if (p.direction == "input") out.push_back(&p);
  return out;
}

std::vector<const LibertyPin*> LibertyCell::outputs() const {
  std::vector<const LibertyPin*> out;
  for (const auto& p : pins)
    if (p.direction == "output") out.push_back(&p);
  return out;
}

const LibertyCell& LibertyLibrary::cell(const std::string& n) const {
  const auto it = cells.find(n);
  if (it == cells.end()) throw std::runtime_error(path + ": library " + name + " has no cell " + n);
  return it->second;
}

LibertyLibrary read_liberty(const std::string& path) {
  return LibParser(read_text_file(path), path).parse();
}

bool eval_liberty_function(const std::string& function, const std::map<std::string, bool>& inputs) {
  return FunctionEval(function, inputs).run();
}

const LibertyCell& strongest_buffer(const LibertyLibrary& lib) {
  const LibertyCell* best = nullptr;
  double best_gain = -1;
  for (const LibertyCell* c : liberty_logic_cells(lib, 1)) {
    const LibertyPin& in = *c->inputs()[0];
    const LibertyPin& out = *c->outputs()[0];
    if (!computes_function(*c, out, [](const std::vector<bool>& b) { return b[0]; })) continue;
    const double gain = in.capacitance > 0 ? out.max_capacitance / in.capacitance : 0.0;
    if (!best || gain > best_gain || (gain == best_gain && c->area < best->area)) {
      best = c;
      best_gain = gain;
    }
  }
  if (!best) throw std::runtime_error(lib.path + ": library " + lib.name + " has no buffer cell");
  return *best;
}

const LibertyCell& nand2_cell(const LibertyLibrary& lib) {
  const LibertyCell* best = nullptr;
  for (const LibertyCell* c : liberty_logic_cells(lib, 2)) {
    const auto nand = [](const std::vector<bool>& b) { return !(b[0] && b[1]); };
    if (!computes_function(*c, *c->outputs()[0], nand)) continue;
    if (!best || c->area < best->area) best = c;
  }
  if (!best) throw std::runtime_error(lib.path + ": library " + lib.name + " has no NAND2 cell");
  return *best;
}

PlainFlipFlop plain_flip_flop(const LibertyLibrary& lib) {
  PlainFlipFlop best;
  for (const auto& [name, c] : lib.cells) {
    if (!c.sequential || c.latch || c.dont_use || c.state_vars.empty()) continue;
    if (c.state.count("clear") || c.state.count("preset")) continue;
    const auto next = c.state.find("next_state");
    const auto clock = c.state.find("clocked_on");
    if (next == c.state.end() || clock == c.state.end()) continue;
    const LibertyPin* d = c.pin(next->second);
    const LibertyPin* clk = c.pin(clock->second);  // "!CLK" names no pin: a falling edge
    if (!d || !clk || d->direction != "input") continue;
    for (const LibertyPin* q : c.outputs()) {
      if (q->function != c.state_vars[0]) continue;
      if (!best.cell || c.area < best.cell->area) best = {&c, d->name, clk->name, q->name};
    }
  }
  return best;
}

PlainFlipFlop required_plain_flip_flop(const LibertyLibrary& lib, const std::string& needed_for) {
  PlainFlipFlop ff = plain_flip_flop(lib);
  if (!ff.cell) {
    throw std::runtime_error(
        lib.path + ": library " + lib.name +
        " has no plain flip-flop (D, clock, Q, no set or reset): " + needed_for);
  }
  return ff;
}

}  // namespace shadesim
