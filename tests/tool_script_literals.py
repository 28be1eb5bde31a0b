#!/usr/bin/python3
"""No C++ string literal under sim/ holds a multi-line tool script.

  tests/tool_script_literals.py [SOURCE_DIR]
  tests/tool_script_literals.py --self-test

The tools' scripts (Yosys, ABC, OpenSTA) are files beside their drivers, which read and fill them
in (sim/eda/common/tool_script.h), so that they can be read, diffed and run by hand. This check
reads every C++ file under sim/ (.cpp, .h, .hpp, .cc), joins adjacent string literals (a script
written as "cmd\\n" "cmd\\n" ... is one literal to the compiler) and fails, naming the file, the
line and the command, when a literal holding a newline has a line whose first word is a tool
command (TOOL_COMMANDS) followed by its arguments, without a '(' or ';'. Text printed to the user ("generic synthesis (synth -flatten; ...)\\n")
starts its lines with other words and passes. Comments are skipped.
The self-test plants a script literal, a raw-string script and an ABC script in a temporary tree
and checks that each is reported, and that printed text and a commented-out script are not.
"""
import os
import re
import shutil
import sys
import tempfile

EXTENSIONS = {".cpp", ".h", ".hpp", ".cc"}
# Commands that start a line of a Yosys, ABC or OpenSTA script and no line of prose: English
# words that are also commands (check, stat, rename, dump, opt, proc, set, buffer) are left out.
TOOL_COMMANDS = {
    # Yosys
    "synth", "synth_ice40", "abc", "opt_clean", "tee", "ltp", "hierarchy", "setattr",
    "write_verilog", "write_json", "write_blif", "read_verilog", "read_json", "dfflibmap",
    "setundef", "splitnets", "chparam", "blackbox", "flatten", "techmap", "memory_map",
    # ABC
    "strash", "scorr", "&get", "&put", "&fraig", "&synch2", "&dch", "&nf", "upsize", "dnsize",
    "stime", "dc2",
    # OpenSTA
    "read_liberty", "link_design", "create_clock", "set_clock_uncertainty", "set_input_delay",
    "set_output_delay", "set_load", "set_driving_cell", "read_spef", "report_checks",
    "report_worst_slack", "report_power", "set_power_activity",
}
# A line's first word, when a space, a tab or the line's end follows it.
FIRST_WORD = re.compile(r"[\s\[{]*([&A-Za-z_][\w&]*)(?:[ \t]|$)")
# A string literal's start: an optional encoding prefix, then " or R"delimiter(.
LITERAL_START = re.compile(r'(?:u8|[uUL])?(R"([^()\\\s]{0,16})\(|")')
ESCAPES = {"n": "\n", "t": "\t", "\\": "\\", '"': '"', "'": "'", "r": "\r", "0": "\0"}


def literals(text):
    """(line, value) of each string literal of C++ `text`, adjacent literals joined into one."""
    out = []
    i, line, n = 0, 1, len(text)
    pending = None  # [line, value] of a literal a following one may join
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
            continue
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            line += text.count("\n", i, j)
            i = j
            continue
        m = LITERAL_START.match(text, i)
        if m and (c == '"' or i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            start_line = line
            if m.group(1).startswith("R"):
                close = ")" + m.group(2) + '"'
                j = text.find(close, m.end())
                j = n if j < 0 else j
                value = text[m.end():j]
                end = j + len(close)
            else:
                value, j = [], m.end()
                while j < n and text[j] != '"':
                    if text[j] == "\\" and j + 1 < n:
                        value.append(ESCAPES.get(text[j + 1], text[j + 1]))
                        j += 2
                    else:
                        value.append(text[j])
                        j += 1
                value = "".join(value)
                end = j + 1
            line += text.count("\n", i, end)
            if pending is not None:
                pending[1] += value
            else:
                pending = [start_line, value]
            i = end
            continue
        if c == "'":  # a character literal: '"' must not open a string
            j = i + 1
            while j < n and text[j] != "'":
                j += 2 if text[j] == "\\" else 1
            i = j + 1
            continue
        if not c.isspace() and pending is not None:
            out.append(tuple(pending))
            pending = None
        if c == "\n":
            line += 1
        i += 1
    if pending is not None:
        out.append(tuple(pending))
    return out


def script_command(value):
    """The first tool command that starts a line of `value`, if it holds a newline."""
    if "\n" not in value:
        return None
    for text in value.split("\n"):
        m = FIRST_WORD.match(text)
        # A '(' or ';' in the line makes it prose about a command (a wrapped --help line such
        # as "abc -g AND,...,MUX (2-input gates, ...)"): no script line of these tools has one.
        if m and m.group(1) in TOOL_COMMANDS and "(" not in text and ";" not in text:
            return m.group(1)
    return None


def check(root):
    """Findings, one line each: file:line: the command a literal's script starts a line with."""
    findings = []
    for d, subdirs, names in os.walk(os.path.join(root, "sim")):
        subdirs.sort()
        for name in sorted(names):
            if os.path.splitext(name)[1] not in EXTENSIONS:
                continue
            path = os.path.join(d, name)
            try:
                with open(path, encoding="utf-8") as f:
                    text = f.read()
            except (OSError, UnicodeDecodeError) as e:
                findings.append(f"{os.path.relpath(path, root)}: cannot read: {e}")
                continue
            for line, value in literals(text):
                command = script_command(value)
                if command:
                    findings.append(f"{os.path.relpath(path, root)}:{line}: a string literal holds "
                                    f"a multi-line tool script ('{command}' starts one of its "
                                    "lines): make it a script file beside its driver "
                                    "(sim/eda/common/tool_script.h)")
    return findings


PLANTED = {
    "sim/eda/planted/yosys.cpp": ('const char* const kFlat =\n'
                                  '    "synth -flatten -top shade_unit\\n"\n'
                                  '    "abc -g AND,NAND\\n";\n', "synth"),
    "sim/eda/planted/raw.cpp": ('const char* kTcl = R"tcl(read_liberty {x}\n'
                                'report_checks -digits 3\n)tcl";\n', "read_liberty"),
    "sim/eda/planted/abc.h": ('inline const char* kAbc = "strash\\n&get -n\\n&nf -D 10\\n";\n',
                              "strash"),
}
CLEAN = {
    "sim/eda/planted/print.cpp": (
        'void f(std::ostream& os) {\n'
        '  os << "generic synthesis (synth -flatten; abc -g AND,NAND; stat -tech cmos)\\n"\n'
        '     << "[area] power: OpenSTA report_power ...\\n" << \'"\';\n'
        '  // "synth -flatten\\n" "abc -g AND\\n" in a comment\n'
        '  /* "report_checks -digits 3\\n" */\n'
        '  const char* one_line = "synth -flatten -top shade_unit";\n'
        '  add_flag("--x", "generic cells after synth -flatten and\\n"\n'
        '           "abc -g AND,NAND,MUX (2-input gates)\\nthen OpenSTA\\n"\n'
        '           "report_power; docs/power.md");\n}\n'),
}


def self_test():
    tmp = tempfile.mkdtemp(prefix="tool_script_literals.")
    failures = []
    try:
        for rel, text in CLEAN.items():
            os.makedirs(os.path.dirname(os.path.join(tmp, rel)), exist_ok=True)
            with open(os.path.join(tmp, rel), "w") as f:
                f.write(text)
        if check(tmp):
            failures.append(f"printed text, help, a comment or a one-line command was reported: "
                            f"{check(tmp)}")
        for rel, (text, _) in PLANTED.items():
            with open(os.path.join(tmp, rel), "w") as f:
                f.write(text)
        got = check(tmp)
        for rel, (_, command) in PLANTED.items():
            if not any(p.startswith(rel + ":") and f"'{command}'" in p for p in got):
                failures.append(f"the script planted in {rel} was not reported: {got}")
        if len(got) != len(PLANTED):
            failures.append(f"expected {len(PLANTED)} findings, got {got}")
        if got and not got[0].startswith("sim/eda/planted/abc.h:1:"):
            failures.append(f"the first finding names the wrong line: {got[0]}")
    finally:
        shutil.rmtree(tmp)
    if failures:
        print("tool_script_literals self-test: FAIL\n  " + "\n  ".join(failures))
        return 1
    print(f"tool_script_literals self-test: pass ({len(PLANTED)} planted scripts reported; "
          "printed text, wrapped help, a comment and a one-line command not)")
    return 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(__file__), ".."))
    if not os.path.isdir(os.path.join(root, "sim")):
        print(f"tool_script_literals: {root} has no sim/ folder")
        return 2
    findings = check(root)
    for p in findings:
        print(f"tool_script_literals: {p}")
    if findings:
        return 1
    print("tool_script_literals: no string literal under sim/ holds a multi-line tool script")
    return 0


if __name__ == "__main__":
    sys.exit(main())
