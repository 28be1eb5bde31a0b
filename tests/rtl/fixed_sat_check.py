#!/usr/bin/python3
"""fixed_sat (rtl/fixed_sat.sv), exhaustively: every input of every small parameter combination
(tests/rtl/tb_fixed_sat.sv under Icarus) against the overflow rule's closed form, worked out here
from the definition (model/fixed_point.h's Overflow): wrap keeps the low OUT_W bits; saturate
clamps to the target's range, an unsigned target's negatives to 0.

  fixed_sat_check.py SOURCE_DIR IVERILOG VVP WORK [--break]

The RTL read is $SHADESIM_RTL_DIR when set (a mutant's copy, scripts/mutate-rtl), else
SOURCE_DIR/rtl. Prints the first mismatches as FAIL lines; exit 0 only when every output matches
and every combination printed every value. --break checks the check: it runs on a copy whose
unsigned-target clamp of negatives is moved to signed targets, and exits 0 only if that fails.
"""
import os
import subprocess
import sys

CLAMP, BROKEN_CLAMP = "OUT_SIGNED == 0 && WRAP == 0", "OUT_SIGNED != 0 && WRAP == 0"

IN_WIDTHS, OUT_WIDTHS = range(2, 8), range(2, 7)


def expected(in_w, out_w, out_signed, wrap, bits):
    value = bits - (1 << in_w) if bits >> (in_w - 1) else bits  # two's complement input
    if not wrap:
        lo, hi = (-(1 << (out_w - 1)), (1 << (out_w - 1)) - 1) if out_signed else (0, (1 << out_w) - 1)
        value = min(max(value, lo), hi)
    return value % (1 << out_w)  # the output's bit pattern


def broken_copy(rtl_file, work):
    text = open(rtl_file).read()
    if CLAMP not in text:
        sys.exit(f"fixed_sat check: {rtl_file} has no `{CLAMP}` to break")
    path = os.path.join(work, "fixed_sat_broken.sv")
    with open(path, "w") as f:
        f.write(text.replace(CLAMP, BROKEN_CLAMP))
    return path


def check(source, iverilog, vvp, work, rtl_file):
    """The FAIL lines of one run (none: every output matches)."""
    image = os.path.join(work, "tb_fixed_sat.vvp")
    r = subprocess.run([iverilog, "-g2012", "-s", "tb_fixed_sat", "-o", image, rtl_file,
                        os.path.join(source, "tests", "rtl", "tb_fixed_sat.sv")],
                       capture_output=True, text=True)
    if r.returncode != 0:
        return [f"FAIL iverilog: {r.stderr.strip()[:400]}"]
    r = subprocess.run([vvp, "-n", image], capture_output=True, text=True)
    lines = r.stdout.splitlines()
    if r.returncode != 0 or "done" not in lines:
        return [f"FAIL vvp ({r.returncode}): {r.stderr.strip()[:400]}"]
    seen, bad = set(), []
    for line in lines:
        f = line.split()
        if not f or f[0] != "sat":
            continue
        in_w, out_w, s, w, bits, out = map(int, f[1:])
        seen.add((in_w, out_w, s, w, bits))
        want = expected(in_w, out_w, s, w, bits)
        if out != want:
            bad.append(f"FAIL IN_W={in_w} OUT_W={out_w} OUT_SIGNED={s} WRAP={w}: "
                       f"in {bits:#x} gave {out:#x}, expected {want:#x}")
    cases = {(i, o, s, w, b) for i in IN_WIDTHS for o in OUT_WIDTHS for s in (0, 1) for w in (0, 1)
             for b in range(1 << i)}
    if seen != cases:
        bad.append(f"FAIL {len(cases - seen)} of {len(cases)} (instance, input) pairs not printed")
    return bad


def main():
    if len(sys.argv) not in (5, 6) or sys.argv[5:] not in ([], ["--break"]):
        sys.exit(__doc__)
    source, iverilog, vvp, work = sys.argv[1:5]
    os.makedirs(work, exist_ok=True)
    rtl_file = os.path.join(os.environ.get("SHADESIM_RTL_DIR") or os.path.join(source, "rtl"),
                            "fixed_sat.sv")
    if sys.argv[5:]:
        bad = check(source, iverilog, vvp, work, broken_copy(rtl_file, work))
        print("\n".join(["the broken clamp was caught:"] + bad[:3]) if bad else
              "FAIL the broken clamp was not caught")
        return 0 if bad else 1
    bad = check(source, iverilog, vvp, work, rtl_file)
    combinations = len(IN_WIDTHS) * len(OUT_WIDTHS) * 4
    inputs = len(OUT_WIDTHS) * 4 * sum(1 << i for i in IN_WIDTHS)
    print("\n".join(bad[:10]) if bad else
          f"ok: {inputs} inputs over {combinations} parameter combinations match the closed form")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
