#!/usr/bin/python3
"""Overflow rules (wrap, saturate) are implemented once: in FixedFormat.

  tests/quantization_home.py [SOURCE_DIR]

Reads the C++ under model/ host/ derive/ explore/ sim/ bench/ tests/golden/ tests/support/
(comments and string literals removed), except model/fixed_point.h and model/fixed_point.cpp,
and exits 1 naming file:line and the pattern for every line that hand-rolls wrap or saturation.
The patterns:

  shift-pair sign extension   x << (64 - wl) ... >> ..., or x << s) >> s      (wrap to wl bits)
  xor-subtract sign extension (x ^ sign) - sign                                (wrap to wl bits)
  sign fill                   ~uint64_t{0} << wl, ~0ull << n                   (wrap to wl bits)
  offset-mask wrap            ((x + offset) & mask) - offset                   (wrap to wl bits)
  modulus wrap                x & (modulus - 1), x -= modulus                  (wrap to wl bits)
  bound select                a ternary or std::min/max/clamp that yields raw_max()/raw_min()
                              (saturate to the format's range)
  bound ternary               x > max_ ? max_ : ..., x < min_ ? min_ : ...     (saturate)

The call sites use FixedFormat::wrap / saturate / fit / quantize instead. The golden model
(tests/golden/) is meant to be independent of FixedFormat: it uses SystemC sc_fix, and must not
hand-roll the rules either. A clamp that is a unit's own rule (W_m's base clamped to 1,
max(0, N.L)) names no format bound and is not matched.

  tests/quantization_home.py --self-test

checks the checker on a small tree it writes: each planted copy (the series engine's former
wrap and saturate among them) must be named, and the FixedFormat calls must pass.
"""
import os
import re
import subprocess
import sys
import tempfile

SCAN_DIRS = ["model", "host", "derive", "explore", "sim", "bench", "tests/golden", "tests/support"]
HOME = {"model/fixed_point.h", "model/fixed_point.cpp"}
EXTS = (".h", ".hpp", ".cpp", ".cc")

PATTERNS = [
    ("shift-pair sign extension", re.compile(r"<<\s*\(?\s*(?:64|128)\s*-")),
    ("shift-pair sign extension", re.compile(r"<<\s*(\w+)\s*\)*\s*>>\s*\1\b")),
    ("xor-subtract sign extension", re.compile(r"\(\s*\w+\s*\^\s*(\w+)\s*\)\s*-\s*\1\b")),
    ("sign fill", re.compile(r"~\s*(?:u?int64_t\s*[{(]\s*0\s*[})]|0[uU]?[lL]*)\s*<<")),
    ("offset-mask wrap", re.compile(r"&\s*\w*mask\w*\s*\)*\s*-\s*\w*offset")),
    ("offset-mask wrap", re.compile(r"\+\s*\w*offset\w*\s*\)*\s*&")),
    ("modulus wrap", re.compile(r"&\s*\(\s*\w*modulus\w*\s*-\s*1\s*\)|-=\s*\w*modulus")),
    ("bound select", re.compile(r"[?:]\s*[\w.>-]*raw_m(?:ax|in)\(\)")),
    ("bound select", re.compile(r"std::(?:min|max|clamp)\s*(?:<[^>]*>)?\s*\([^;]*raw_m(?:ax|in)\(\)")),
    ("bound ternary", re.compile(r"\b(\w+)\s*>=?\s*(\w*max\w*)\s*\?\s*\2\b")),
    ("bound ternary", re.compile(r"\b(\w+)\s*<=?\s*(\w*min\w*)\s*\?\s*\2\b")),
]


def strip(text):
    """C++ text with comments and string/char literals blanked (line numbers kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def scan(root):
    found = []
    for d in SCAN_DIRS:
        for dirpath, _, names in os.walk(os.path.join(root, d)):
            for name in sorted(names):
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, root)
                if not name.endswith(EXTS) or rel in HOME:
                    continue
                with open(path, encoding="utf-8", errors="replace") as f:
                    lines = strip(f.read()).split("\n")
                for number, line in enumerate(lines, 1):
                    for what, pattern in PATTERNS:
                        if pattern.search(line):
                            found.append(f"{rel}:{number}: {what}: {line.strip()}")
                            break
    return found


PLANTED = {
    # A hand-rolled wrap as a shift pair.
    "model/engine_a.h": "return static_cast<int64_t>(static_cast<uint64_t>(s) << shift_) >> shift_;\n",
    "model/engine_b.h": "int64_t w = int64_t(uint64_t(x) << (64 - wl)) >> (64 - wl);\n",
    # A hand-rolled wrap by mask and a hand-rolled saturate.
    "model/bank_wrap.h": "return static_cast<int64_t>((static_cast<uint64_t>(x + offset_)) & mask_) - offset_;\n",
    "model/bank_sat.h": "int64_t saturate(int64_t x) const { return x > max_ ? max_ : (x < min_ ? min_ : x); }\n",
    "host/xor.cpp": "out.push_back(static_cast<int64_t>((field ^ sign) - sign));\n",
    "tests/golden/fill.cpp": "if (neg) bits |= ~uint64_t{0} << format.wl;\n",
    "sim/mod.cpp": "Int128 w = v & (modulus - 1);\n",
    "bench/sel.cpp": "return v > f.raw_max() ? f.raw_max() : v;\n",
    "tests/support/clamp.h": "const int64_t c = std::clamp<int64_t>(x, f.raw_min(), f.raw_max());\n",
    "host/sat_lo.cpp": "y = y < lo_min ? lo_min : y;\n",
}
CLEAN = {
    "model/fixed_point.h": "return static_cast<int64_t>(static_cast<uint64_t>(raw) << (64 - wl)) >> (64 - wl);\n",
    "model/uses.h": ("v = series.fit(v + d);  // x > max_ ? max_ : x in a comment is fine\n"
                     "const int64_t w = f.wrap(x), s = f.saturate(x);\n"
                     "if (b > one) b = one;\n"
                     "const char* text = \"(field ^ sign) - sign\";\n"
                     "bool fits = raw >= f.raw_min() && raw <= f.raw_max();\n"
                     "b = std::min(b, int64_t{1} << b_frac);\n"),
}


def self_test():
    with tempfile.TemporaryDirectory() as root:
        for rel, text in {**PLANTED, **CLEAN}.items():
            os.makedirs(os.path.dirname(os.path.join(root, rel)), exist_ok=True)
            with open(os.path.join(root, rel), "w") as f:
                f.write(text)
        r = subprocess.run([sys.executable, os.path.abspath(__file__), root],
                           capture_output=True, text=True)
        named = {line.split(":")[0] for line in r.stdout.splitlines() if ":" in line}
        problems = [f"planted copy not named: {p}" for p in PLANTED if p not in named]
        problems += [f"clean file named: {p}" for p in CLEAN if p in named]
        if r.returncode != 1:
            problems.append(f"exit code {r.returncode}, expected 1")
        if problems:
            print("quantization_home self-test FAILED:", *problems, "output:", r.stdout, sep="\n  ")
            return 1
        print(f"quantization_home self-test: the {len(PLANTED)} planted copies named, "
              f"the {len(CLEAN)} clean files passed")
        return 0


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--self-test":
        return self_test()
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1
                           else os.path.join(os.path.dirname(__file__), ".."))
    found = scan(root)
    for line in found:
        print(line)
    if found:
        print(f"{len(found)} hand-rolled wrap/saturate outside FixedFormat (model/fixed_point.h);"
              " use FixedFormat::wrap / saturate / fit / quantize")
        return 1
    print("quantization_home: no wrap or saturate outside FixedFormat")
    return 0


if __name__ == "__main__":
    sys.exit(main())
