#!/usr/bin/env python3
"""Formal equivalence of shade_unit before and after its split into control modules (issue 22):
Yosys equiv_make / equiv_simple / equiv_induct between the monolithic rtl/shade_unit.sv of a
reference commit (14837f3, read with `git archive`) and this tree's rtl/ (rtl/files.f), both
flattened, for one parameter set.

  equiv_split.py YOSYS SOURCE_DIR WORK [-set NAME VALUE]...

The two designs' registers are matched by name: a flattened register of the new tree,
u_<module>.<name>, is renamed to <name> when the old design has that name (the split kept the
register names), so the induction has the old state to lean on; the rest are matched by
equiv_make's own structural pass. Exit 0 only when equiv_status finds no unproven cell.
"""
import os
import re
import subprocess
import sys
import tarfile
import io

REFERENCE = "14837f3"


def run_yosys(yosys, script, log):
    r = subprocess.run([yosys, "-q", "-l", log, "-p", script], capture_output=True, text=True)
    if r.returncode != 0:
        sys.stderr.write(open(log).read()[-4000:] if os.path.exists(log) else r.stderr)
        sys.exit(f"equiv_split: yosys failed (log {log})")


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    yosys, src, work = sys.argv[1:4]
    chparam = " ".join(sys.argv[4:])
    os.makedirs(work, exist_ok=True)
    # The reference tree's rtl/.
    old_dir = os.path.join(work, "old")
    if not os.path.isdir(os.path.join(old_dir, "rtl")):
        tar = subprocess.run(["git", "-C", src, "archive", REFERENCE, "rtl"], capture_output=True)
        if tar.returncode != 0:
            sys.exit(f"equiv_split: git archive {REFERENCE} rtl failed: {tar.stderr.decode()}")
        tarfile.open(fileobj=io.BytesIO(tar.stdout)).extractall(old_dir)
    old_files = [os.path.join(old_dir, "rtl", f) for f in (
        "shade_pkg.sv", "fixed_round.sv", "fixed_sat.sv", "span_setup.sv", "series_engine.sv",
        "lane_fanout.sv", "pixel_combine.sv", "exponent_lut.sv", "schlick_divider.sv",
        "wpow_unit.sv", "specular_unit.sv", "fault_select.sv", "shade_unit.sv")]
    new_files = []
    with open(os.path.join(src, "rtl", "files.f")) as f:
        for line in f:
            line = line.strip()
            if line and not line.startswith("//"):
                new_files.append(os.path.join(src, "rtl", line))
    cp = f"chparam {chparam} shade_unit; " if chparam else ""
    # Elaborate both; flatten; memories to registers; keep public names.
    prep = ("hierarchy -check -top shade_unit; proc; flatten; opt_clean; memory; opt_clean; async2sync; "
            "rename -top shade_unit; ")
    designs = {}
    for name, files in (("gold", old_files), ("gate", new_files)):
        il = os.path.join(work, f"{name}.il")
        run_yosys(yosys, f"read_verilog -sv {' '.join(files)}; {cp}{prep}"
                  f"rename shade_unit {name}; write_rtlil {il}; "
                  f"tee -q -o {os.path.join(work, name + '_wires.txt')} select -list w:*",
                  os.path.join(work, f"{name}_prep.log"))
        designs[name] = il
    gold_wires = set()
    for line in open(os.path.join(work, "gold_wires.txt")):
        line = line.strip()
        if line.startswith("gold/"):
            gold_wires.add(line[len("gold/"):])
    # Unnamed generate blocks (an `else if` chain) are genblk<N>, numbered per module: compare
    # names without them.
    def norm(name):
        return re.sub(r"genblk\d+\.", "", name)
    gold_by_norm = {}
    for w in gold_wires:
        gold_by_norm.setdefault(norm(w), []).append(w)
    renames = []
    for line in open(os.path.join(work, "gate_wires.txt")):
        line = line.strip()
        if not line.startswith("gate/"):
            continue
        w = line[len("gate/"):]
        m = re.match(r"^u_[a-z_]+\.(.*)$", w)
        if not m or w.startswith("$"):
            continue
        old = gold_by_norm.get(norm(m.group(1)), [])
        if len(old) == 1:
            renames.append((w, old[0]))
    gate_names = {line.strip()[len("gate/"):] for line in open(os.path.join(work, "gate_wires.txt"))
                  if line.strip().startswith("gate/")}
    ren = "".join(f"rename \\{a} \\{b}; " for a, b in renames if b not in gate_names)
    script = (f"read_rtlil {designs['gold']}; read_rtlil {designs['gate']}; "
              f"cd gate; {ren}cd; "
              "equiv_make gold gate equiv; hierarchy -top equiv; "
              "equiv_simple -seq 4; equiv_induct -seq 4; "
              f"tee -o {os.path.join(work, 'status.txt')} equiv_status")
    run_yosys(yosys, script, os.path.join(work, "equiv.log"))
    status = open(os.path.join(work, "status.txt")).read()
    m = re.search(r"Found (\d+) \$equiv cells.*?Of those cells (\d+) are proven and (\d+) are unproven",
                  status, re.S)
    if not m:
        sys.exit(f"equiv_split: no equiv_status summary in {work}/status.txt:\n{status}")
    total, proven, unproven = map(int, m.groups())
    print(f"equiv_split [{chparam or 'defaults'}]: {total} $equiv cells, {proven} proven, "
          f"{unproven} unproven; {len(renames)} registers matched by name")
    if unproven:
        print(status[-3000:])
        sys.exit(1)


if __name__ == "__main__":
    main()
