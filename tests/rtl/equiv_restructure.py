#!/usr/bin/env python3
"""Formal equivalence of shade_unit across a restructuring of its modules: Yosys
equiv_make / equiv_simple / equiv_induct between rtl/ of a reference commit (read with
`git archive`) and this tree's rtl/, both flattened, for one parameter set.

  equiv_restructure.py YOSYS SOURCE_DIR WORK REFERENCE [NAME=VALUE]...

Both trees are read through their own rtl/files.f. Registers are matched by name: a flattened
register of this tree whose name, with one level of hierarchy removed (a module that now wraps
others, e.g. u_span_source.), is unique in the reference design is renamed to it, so that the
induction has the old state to lean on; the rest are left to equiv_make's structural matching.
Exit 0 only when equiv_status finds no unproven $equiv cell.
"""
import io
import os
import re
import subprocess
import sys
import tarfile


def run_yosys(yosys, script, log):
    r = subprocess.run([yosys, "-q", "-l", log, "-p", script], capture_output=True, text=True)
    if r.returncode != 0:
        sys.stderr.write(open(log).read()[-4000:] if os.path.exists(log) else r.stderr)
        sys.exit(f"equiv_restructure: yosys failed (log {log})")


def rtl_files(root):
    with open(os.path.join(root, "rtl", "files.f")) as f:
        return [os.path.join(root, "rtl", l.strip()) for l in f
                if l.strip() and not l.strip().startswith("//")]


def wires(path, prefix):
    return {l.strip()[len(prefix):] for l in open(path) if l.strip().startswith(prefix)}


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    yosys, src, work, reference = sys.argv[1:5]
    params = sys.argv[5:]
    for p in params:
        if not re.fullmatch(r"[A-Z_0-9]+=\S+", p):
            sys.exit(f"equiv_restructure: parameter '{p}' is not NAME=VALUE")
    os.makedirs(work, exist_ok=True)
    old_dir = os.path.join(work, "reference")
    if not os.path.isdir(os.path.join(old_dir, "rtl")):
        tar = subprocess.run(["git", "-C", src, "archive", reference, "rtl"], capture_output=True)
        if tar.returncode != 0:
            sys.exit(f"equiv_restructure: git archive {reference} rtl failed: "
                     f"{tar.stderr.decode()}")
        tarfile.open(fileobj=io.BytesIO(tar.stdout)).extractall(old_dir)
    chparam = "".join(f"chparam -set {p.split('=')[0]} {p.split('=')[1]} shade_unit; "
                      for p in params)
    prep = ("hierarchy -check -top shade_unit; proc; flatten; opt_clean; memory; opt_clean; "
            "async2sync; rename -top shade_unit; ")
    il = {}
    for name, root in (("gold", old_dir), ("gate", src)):
        il[name] = os.path.join(work, f"{name}.il")
        run_yosys(yosys, f"read_verilog -sv {' '.join(rtl_files(root))}; {chparam}{prep}"
                  f"rename shade_unit {name}; write_rtlil {il[name]}; "
                  f"tee -q -o {os.path.join(work, name + '_wires.txt')} select -list w:*",
                  os.path.join(work, f"{name}_prep.log"))
    gold = wires(os.path.join(work, "gold_wires.txt"), "gold/")
    gate = wires(os.path.join(work, "gate_wires.txt"), "gate/")
    renames = []
    for w in sorted(gate - gold):
        if w.startswith("$"):
            continue
        parts = w.split(".")
        found = {".".join(parts[:i] + parts[i + 1:]) for i in range(len(parts) - 1)} & gold
        if len(found) == 1:
            renames.append((w, found.pop()))
    ren = "".join(f"rename \\{a} \\{b}; " for a, b in renames if b not in gate)
    script = (f"read_rtlil {il['gold']}; read_rtlil {il['gate']}; cd gate; {ren}cd; "
              "equiv_make gold gate equiv; hierarchy -top equiv; "
              "equiv_simple -seq 4; equiv_induct -seq 4; "
              f"tee -o {os.path.join(work, 'status.txt')} equiv_status")
    run_yosys(yosys, script, os.path.join(work, "equiv.log"))
    status = open(os.path.join(work, "status.txt")).read()
    m = re.search(r"Found (\d+) \$equiv cells.*?Of those cells (\d+) are proven and (\d+) are "
                  r"unproven", status, re.S)
    if not m:
        sys.exit(f"equiv_restructure: no equiv_status summary in {work}/status.txt:\n{status}")
    total, proven, unproven = map(int, m.groups())
    print(f"equiv_restructure [{' '.join(params) or 'defaults'}] against {reference}: {total} "
          f"$equiv cells, {proven} proven, {unproven} unproven; {len(renames)} names matched "
          "across the new hierarchy")
    if unproven or total == 0:
        print(status[-3000:])
        sys.exit(1)


if __name__ == "__main__":
    main()
