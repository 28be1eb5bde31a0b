// Readers of a Liberty library's cells and of a Yosys-written mapped netlist
// (sim/eda/power/power_netlist.h).
#include "sim/eda/power/power_netlist.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <functional>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

#include "model/text_file.h"

namespace shadesim {
// A named namespace, not an anonymous one: sim/ is compiled as unity files (CMakeLists.txt).
namespace power_netlist_impl {

std::string slurp(const std::string& path, const char* what) {
  try {
    return read_text_file(path);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string(what) + ": " + e.what());
  }
}

// ---- Liberty ------------------------------------------------------------------------------

struct LibToken {
  enum Kind { kWord, kString, kPunct, kEnd } kind = kEnd;
  std::string text;
};

class LibLexer {
 public:
  explicit LibLexer(const std::string& s) : s_(s) {}
  LibToken next() {
    skip();
    if (i_ >= s_.size()) return {LibToken::kEnd, ""};
    const char c = s_[i_];
    if (c == '"') {
      const size_t end = s_.find('"', i_ + 1);
      const size_t stop = end == std::string::npos ? s_.size() : end;
      LibToken t{LibToken::kString, s_.substr(i_ + 1, stop - i_ - 1)};
      i_ = stop + 1;
      return t;
    }
    if (std::string("(){}:;,").find(c) != std::string::npos) {
      ++i_;
      return {LibToken::kPunct, std::string(1, c)};
    }
    const size_t start = i_;
    while (i_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[i_])) &&
           std::string("(){}:;,\"").find(s_[i_]) == std::string::npos)
      ++i_;
    return {LibToken::kWord, s_.substr(start, i_ - start)};
  }

 private:
  void skip() {
    for (;;) {
      while (i_ < s_.size() && (std::isspace(static_cast<unsigned char>(s_[i_])) || s_[i_] == '\\'))
        ++i_;
      if (s_.compare(i_, 2, "/*") != 0) return;
      const size_t end = s_.find("*/", i_ + 2);
      i_ = end == std::string::npos ? s_.size() : end + 2;
    }
  }
  const std::string& s_;
  size_t i_ = 0;
};

// Walks the group structure, tracking cell / ff / latch / pin groups and the pin attributes.
class LibertyWalker {
 public:
  explicit LibertyWalker(const std::string& text) : lex_(text) {}
  std::map<std::string, LibertyCellPins> run() {
    for (LibToken t = lex_.next(); t.kind != LibToken::kEnd; t = lex_.next()) {
      if (t.kind == LibToken::kPunct && t.text == "}") {
        if (!stack_.empty()) stack_.pop_back();
      } else if (t.kind == LibToken::kWord) {
        statement(t.text);
      }
    }
    return cells_;
  }

 private:
  struct Group {
    std::string kind;
    std::vector<std::string> args;
  };
  void statement(const std::string& name) {
    LibToken t = lex_.next();
    if (t.kind == LibToken::kPunct && t.text == ":") {
      std::string value;
      for (t = lex_.next();
           t.kind != LibToken::kEnd && !(t.kind == LibToken::kPunct && t.text == ";");
           t = lex_.next())
        value += (value.empty() ? "" : " ") + t.text;
      attribute(name, value);
    } else if (t.kind == LibToken::kPunct && t.text == "(") {
      std::vector<std::string> args;
      for (t = lex_.next();
           t.kind != LibToken::kEnd && !(t.kind == LibToken::kPunct && t.text == ")");
           t = lex_.next())
        if (t.kind != LibToken::kPunct) args.push_back(t.text);
      t = lex_.next();
      if (t.kind == LibToken::kPunct && t.text == "{") open(name, args);
      // ';' (a complex attribute) or nothing: no group
    }
  }
  void open(const std::string& kind, const std::vector<std::string>& args) {
    stack_.push_back({kind, args});
    if (kind == "cell" && !args.empty()) cell_ = args[0];
    if ((kind == "ff" || kind == "latch") && in("cell") && args.size() >= 1) {
      cells_[cell_].state_pin = args[0];
      if (args.size() >= 2) cells_[cell_].state_pin_inv = args[1];
    }
    if (kind == "cell") cells_[cell_];
  }
  void attribute(const std::string& name, const std::string& value) {
    if (stack_.empty() || stack_.back().kind != "pin" || !in("cell")) return;
    for (const auto& pin : stack_.back().args) {
      if (name == "direction") cells_[cell_].direction[pin] = value;
      if (name == "function") cells_[cell_].function[pin] = value;
    }
  }
  bool in(const char* kind) const {
    for (const auto& g : stack_)
      if (g.kind == kind) return true;
    return false;
  }
  LibLexer lex_;
  std::vector<Group> stack_;
  std::string cell_;
  std::map<std::string, LibertyCellPins> cells_;
};

// ---- Verilog --------------------------------------------------------------------------------

class VerilogLexer {
 public:
  explicit VerilogLexer(const std::string& s) : s_(s) {}
  // The next token; "" at the end. Escaped identifiers keep their backslash.
  std::string next() {
    skip();
    if (i_ >= s_.size()) return "";
    const char c = s_[i_];
    size_t start = i_;
    if (c == '\\') {
      while (i_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
      return s_.substr(start, i_ - start);
    }
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '$' || c == '\'') {
      while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_' ||
                                s_[i_] == '$' || s_[i_] == '\''))
        ++i_;
      return s_.substr(start, i_ - start);
    }
    ++i_;
    return std::string(1, c);
  }

 private:
  void skip() {
    for (;;) {
      while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
      if (s_.compare(i_, 2, "//") == 0) {
        const size_t end = s_.find('\n', i_);
        i_ = end == std::string::npos ? s_.size() : end;
      } else if (s_.compare(i_, 2, "/*") == 0 || s_.compare(i_, 2, "(*") == 0) {
        const size_t end = s_.find(s_[i_] == '/' ? "*/" : "*)", i_ + 2);
        i_ = end == std::string::npos ? s_.size() : end + 2;
      } else {
        return;
      }
    }
  }
  const std::string& s_;
  size_t i_ = 0;
};

// One statement's tokens, up to and without its ';' (or "endmodule", which has none).
std::vector<std::string> statement_tokens(VerilogLexer& lex) {
  std::vector<std::string> toks;
  for (std::string t = lex.next(); !t.empty(); t = lex.next()) {
    if (t == ";") return toks;
    toks.push_back(t);
    if (toks.size() == 1 && t == "endmodule") return toks;
  }
  return toks;
}

// A token as a name: an escaped identifier without its backslash.
std::string bare(const std::string& tok) {
  return !tok.empty() && tok[0] == '\\' ? tok.substr(1) : tok;
}

// Tokens [i, end) of a net expression as one name: "a", "a[3]"; a concatenation stays as text.
std::string join_tokens(const std::vector<std::string>& t, size_t i, size_t end) {
  std::string s;
  for (; i < end; ++i) s += bare(t[i]);
  return s;
}

// The same tokens as Verilog text (an escaped identifier ends at a space).
std::string join_text(const std::vector<std::string>& t, size_t i, size_t end) {
  std::string s;
  for (; i < end; ++i) s += t[i] + (t[i][0] == '\\' ? " " : "");
  return s;
}

// CELL NAME ( .PIN ( net ) , ... )
bool parse_instance(const std::vector<std::string>& t, NetlistInstance& inst) {
  if (t.size() < 4 || t[2] != "(") return false;
  inst.cell = bare(t[0]);
  inst.name = bare(t[1]);
  inst.pins.clear();
  for (size_t i = 3; i + 2 < t.size(); ++i) {
    if (t[i] != "." || t[i + 2] != "(") continue;
    size_t depth = 1, j = i + 3;
    for (; j < t.size() && depth > 0; ++j) depth += t[j] == "(" ? 1 : t[j] == ")" ? -1 : 0;
    inst.pins.push_back({bare(t[i + 1]), join_tokens(t, i + 3, j - 1), join_text(t, i + 3, j - 1)});
    i = j - 1;
  }
  return true;
}

// input [h:l] a, b  ->  bits of each name.
void add_ports(const std::vector<std::string>& t, std::vector<std::string>& out) {
  int hi = -1, lo = -1;
  size_t i = 1;
  if (i < t.size() && t[i] == "[") {
    hi = std::stoi(t[i + 1]);
    lo = std::stoi(t[i + 3]);
    i += 5;
  }
  for (; i < t.size(); ++i) {
    if (t[i] == "," || t[i] == "wire") continue;
    if (hi < 0) {
      out.push_back(bare(t[i]));
      continue;
    }
    for (int b = std::min(hi, lo); b <= std::max(hi, lo); ++b)
      out.push_back(bare(t[i]) + "[" + std::to_string(b) + "]");
  }
}

}  // namespace power_netlist_impl

std::vector<std::string> LibertyCellPins::state_outputs() const {
  std::vector<std::string> out;
  for (const auto& [pin, f] : function) {
    std::string g = f;
    g.erase(std::remove_if(
                g.begin(), g.end(),
                [](char c) { return c == ' ' || c == '!' || c == '(' || c == ')' || c == '\''; }),
            g.end());
    if (!state_pin.empty() && (g == state_pin || (!state_pin_inv.empty() && g == state_pin_inv)))
      out.push_back(pin);
  }
  return out;
}

bool LibertyCellPins::inverted_output(const std::string& pin) const {
  const auto f = function.find(pin);
  if (f == function.end()) return false;
  const bool negated =
      f->second.find('!') != std::string::npos || f->second.find('\'') != std::string::npos;
  const bool names_inv =
      !state_pin_inv.empty() && f->second.find(state_pin_inv) != std::string::npos;
  return negated != names_inv;
}

std::map<std::string, LibertyCellPins> read_liberty_cells(const std::string& liberty_path) {
  const std::string text = power_netlist_impl::slurp(liberty_path, "liberty");
  auto cells = power_netlist_impl::LibertyWalker(text).run();
  if (cells.empty()) throw std::runtime_error("liberty: no cell in " + liberty_path);
  return cells;
}

MappedNetlist read_mapped_netlist(const std::string& verilog_path, const std::string& top) {
  using namespace power_netlist_impl;
  const std::string text = slurp(verilog_path, "netlist");
  VerilogLexer lex(text);
  MappedNetlist n;
  bool in_top = false, found = false;
  for (;;) {
    const std::vector<std::string> t = statement_tokens(lex);
    if (t.empty()) break;
    if (t[0] == "module") {
      in_top = t.size() > 1 && bare(t[1]) == top;
      found = found || in_top;
    } else if (t[0] == "endmodule") {
      in_top = false;
    } else if (!in_top || t[0] == "wire" || t[0] == "reg" || t[0] == "output" || t[0] == "inout") {
      continue;
    } else if (t[0] == "input") {
      add_ports(t, n.inputs);
    } else if (t[0] == "assign") {
      const auto eq = std::find(t.begin(), t.end(), "=");
      if (eq == t.end()) continue;
      const size_t e = static_cast<size_t>(eq - t.begin());
      n.assigns.emplace_back(join_tokens(t, 1, e), join_tokens(t, e + 1, t.size()));
    } else {
      NetlistInstance inst;
      if (parse_instance(t, inst)) n.instances.push_back(inst);
    }
  }
  if (!found) throw std::runtime_error("netlist: no module " + top + " in " + verilog_path);
  return n;
}

int constant_value(const std::string& net) {
  const auto q = net.find('\'');
  if (q == std::string::npos || q + 2 > net.size()) return -1;
  const std::string digits = net.substr(q + 2);
  if (digits.empty() || digits.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
    return -1;
  return digits.find_first_not_of('0') == std::string::npos ? 0 : 1;
}

std::map<std::string, std::vector<std::string>> net_aliases(const MappedNetlist& n) {
  std::map<std::string, std::string> parent;
  const std::function<std::string(const std::string&)> root = [&](const std::string& a) {
    auto it = parent.find(a);
    if (it == parent.end() || it->second == a) return a;
    return it->second = root(it->second);
  };
  for (const auto& [l, r] : n.assigns) {
    if (l.find('{') != std::string::npos || r.find('{') != std::string::npos) continue;
    if (constant_value(l) >= 0 || constant_value(r) >= 0) continue;
    parent.emplace(l, l);
    parent.emplace(r, r);
    const std::string a = root(l), b = root(r);
    if (a != b) parent[a] = b;
  }
  std::map<std::string, std::vector<std::string>> groups;
  for (const auto& [name, p] : parent) groups[root(name)].push_back(name);
  std::map<std::string, std::vector<std::string>> out;
  for (const auto& [r, names] : groups)
    for (const auto& name : names) out[name] = names;
  return out;
}

std::string add_input_ports(const std::string& verilog, const std::string& top,
                            const std::vector<std::pair<std::string, std::string>>& ports) {
  const std::regex head("(^|\\n)\\s*module\\s+\\\\?" +
                        std::regex_replace(top, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
                        "\\s*\\(");
  std::smatch m;
  if (!std::regex_search(verilog, m, head))
    throw std::runtime_error("netlist: no module " + top + " to add ports to");
  const size_t open = static_cast<size_t>(m.position(0) + m.length(0));
  const size_t end = verilog.find("endmodule", open);
  if (end == std::string::npos) throw std::runtime_error("netlist: module " + top + " never ends");
  std::string names, body;
  for (const auto& [port, net] : ports) {
    names += port + ", ";
    body += "  input " + port + ";\n  assign " + net + " = " + port + ";\n";
  }
  return verilog.substr(0, open) + names + verilog.substr(open, end - open) + body +
         verilog.substr(end);
}

}  // namespace shadesim
