#!/usr/bin/env python3
"""Holds the source tree's layers: every #include "dir/file.h" of a C++ file must name a folder
its own folder may use (LAYERS below, the one home of the rule; docs/architecture.md describes
it). A folder may always include its own headers.

    tests/include_layers.py SOURCE_DIR    exit 1 listing every upward or sideways include
    tests/include_layers.py --self-test   shows the check fails on a planted upward include,
                                          on a source folder LAYERS does not name, and on an
                                          include of a folder that does not exist
"""
import pathlib
import re
import shutil
import sys
import tempfile

# folder -> the folders it may include (besides itself). Lower layers first.
LAYERS = {
    "model": [],
    "host": ["model"],
    "derive": ["host", "model"],
    "explore": ["derive", "host", "model"],
    "sim/harness": ["model"],
    "sim/icarus": ["sim/harness", "model"],
    # The EDA drivers: one folder per tool, each on the shared plumbing of common/.
    "sim/eda/common": ["model"],
    "sim/eda/verilator": ["sim/eda/common", "sim/harness", "model"],
    "sim/eda/sta": ["sim/eda/common", "model"],
    "sim/eda/yosys": ["sim/eda/common", "model"],
    # The iCE40 flow is Yosys's synth_ice40 and nextpnr: it reads Yosys's stat report.
    "sim/eda/ice40": ["sim/eda/yosys", "sim/eda/common", "model"],
    # Power is OpenSTA's report_power on the liberty flow's netlist, under activity read from
    # an FST trace (the trace's cycle protocol is the harness's).
    "sim/eda/power": ["sim/eda/sta", "sim/eda/common", "sim/harness", "model"],
    # Layout draws its picture with the host's PNG writer.
    "sim/eda/layout": ["sim/eda/sta", "sim/eda/power", "sim/eda/yosys", "sim/eda/common",
                       "host", "model"],
    # The engines of the commands, on every tool driver.
    "sim/engines": ["sim/eda/common", "sim/eda/verilator", "sim/eda/yosys", "sim/eda/ice40",
                    "sim/eda/sta", "sim/eda/power", "sim/eda/layout", "sim/harness", "explore",
                    "derive", "host", "model"],
    "sim/regress": ["sim/engines", "sim/eda/common", "sim/eda/verilator", "sim/eda/yosys",
                    "sim/harness", "derive", "host", "model"],
    "sim/report": ["sim/regress", "sim/engines", "sim/eda/common", "sim/eda/verilator",
                   "sim/eda/yosys", "sim/eda/sta", "sim/eda/power", "sim/eda/layout", "model"],
    "sim/cli": ["sim/report", "sim/regress", "sim/engines", "sim/eda/common",
                "sim/eda/verilator", "sim/eda/yosys", "sim/eda/sta", "sim/eda/power",
                "sim/eda/layout", "sim/harness", "explore", "derive", "host", "model"],
}

# Includes that cross the layers, each with the reason it is still there (none today). The check
# fails on any other, and on an entry here that no longer occurs (so the list only shrinks).
KNOWN_CROSSINGS = {}  # (folder, the folder it includes) -> why, while it is still there

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
SOURCE_SUFFIXES = {".h", ".cpp"}
LAYERED_ROOTS = ("model", "host", "derive", "explore", "sim")


def folder_of(rel: pathlib.PurePosixPath, folders) -> str:
    """The longest LAYERS folder that holds rel, or its parent folder when none does."""
    parts = rel.parts[:-1]
    for n in range(len(parts), 0, -1):
        candidate = "/".join(parts[:n])
        if candidate in folders:
            return candidate
    return "/".join(parts)


def check(root: pathlib.Path, crossings=None) -> list:
    crossings = KNOWN_CROSSINGS if crossings is None else crossings
    problems = []
    used_crossings = set()
    layered = set(LAYERS)
    # tests/, bench/, rtl/ and build folders may include anything.
    sources = [p for top in LAYERED_ROOTS if (root / top).is_dir()
               for p in (root / top).rglob("*") if p.suffix in SOURCE_SUFFIXES and p.is_file()]
    for path in sorted(sources):
        rel = pathlib.PurePosixPath(path.relative_to(root).as_posix())
        own = folder_of(rel, layered)
        if own not in LAYERS:
            problems.append(f"{rel}: its folder {own}/ is in no layer of tests/include_layers.py")
            continue
        text = path.read_text(encoding="utf-8", errors="replace")
        for target in INCLUDE.findall(text):
            tpath = pathlib.PurePosixPath(target)
            if tpath.parts[0] not in LAYERED_ROOTS:
                continue  # a library's or a generated header
            if not (root / target).exists():
                problems.append(f"{rel}: includes {target}, which does not exist")
                continue
            theirs = folder_of(tpath, layered)
            if theirs == own or theirs in LAYERS[own]:
                continue
            if (own, theirs) in crossings:
                used_crossings.add((own, theirs))
                continue
            problems.append(f"{rel}: includes {target} — {own}/ may include only "
                            f"{', '.join(LAYERS[own]) or 'itself'}")
    for crossing in sorted(set(crossings) - used_crossings):
        problems.append(f"tests/include_layers.py: the known crossing {crossing[0]} -> "
                        f"{crossing[1]} no longer occurs; remove it from KNOWN_CROSSINGS")
    return problems


def self_test() -> int:
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)

        def write(rel, text):
            p = root / rel
            p.parent.mkdir(parents=True, exist_ok=True)
            p.write_text(text)

        write("model/a.h", "#pragma once\n")
        write("host/b.h", '#include "model/a.h"\n')
        write("sim/eda/yosys/c.h", '#include "sim/eda/ice40/d.h"\n#include "sim/eda/sta/e.h"\n')
        write("sim/eda/ice40/d.h", "")
        write("sim/eda/sta/e.h", "")
        planted = {("sim/eda/yosys", "sim/eda/ice40"): "planted",
                   ("sim/eda/yosys", "sim/eda/sta"): "planted"}
        clean = check(root, planted)
        if clean:
            print("self-test: a tree with only allowed includes was refused:", *clean, sep="\n  ")
            return 1
        cases = {
            "an upward include": ("model/up.h", '#include "host/b.h"\n'),
            "a folder in no layer": ("sim/newtool/x.cpp", '#include "model/a.h"\n'),
            "an include of nothing": ("host/y.cpp", '#include "host/missing.h"\n'),
        }
        for name, (rel, text) in cases.items():
            write(rel, text)
            found = check(root, planted)
            (root / rel).unlink()
            if not any(rel in p for p in found):
                print(f"self-test: {name} ({rel}) was not reported")
                return 1
        shutil.rmtree(root / "sim/eda/ice40")
        write("sim/eda/yosys/c.h", '#include "sim/eda/sta/e.h"\n')
        if not any("no longer occurs" in p for p in check(root, planted)):
            print("self-test: a known crossing that no longer occurs was not reported")
            return 1
    print("include_layers self-test: an upward include, an unlayered folder, a missing header "
          "and a stale known crossing are each reported")
    return 0


def main(argv) -> int:
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    problems = check(pathlib.Path(argv[1]))
    for p in problems:
        print(p)
    if problems:
        print(f"include_layers: {len(problems)} include(s) break the layers "
              "(tests/include_layers.py holds them)")
        return 1
    print(f"include_layers: every include of model/, host/, derive/, explore/ and sim/ keeps "
          f"the {len(LAYERS)} layers")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
