#!/usr/bin/env python3
"""Flat-synthesise shade_unit with Yosys and fail when a pixel output bit is constant or an
alias of another output bit in the netlist.

usage: yosys_outputs_check.py YOSYS OUT_PREFIX rtl/*.sv   (shade_pkg.sv first)
       yosys_outputs_check.py - PREFIX   (check PREFIX.v as it is: the checker's own test)
YOSYS_CHPARAM: chparam arguments for shade_unit (a small multi-lane unit keeps it quick).

In a correct netlist of a multi-lane unit every bit of pix_colour_o, pix_x_o and pix_y_o is its
own flip-flop: the lanes shade different pixels. Yosys 0.23 once read a packed array of packed
structs (the slot's metadata line) as single bits, so its netlist kept one metadata bit: lanes
1..3 of pix_colour_o came out as one merged register (write_verilog: `assign {pix_colour_o[..]}
= {pix_colour_o[..]}`) and pix_x_o / pix_y_o as constants, while Verilator and Icarus simulated
the RTL bit-exactly. Output bits driven from a constant or from another output bit are such a
misreading (or logic that really is dead), and fail here.
"""
import os
import re
import subprocess
import sys

PORTS = ("pix_colour_o", "pix_x_o", "pix_y_o")


def main():
    if len(sys.argv) < 3 or (sys.argv[1] != "-" and len(sys.argv) < 4):
        sys.exit(__doc__)
    yosys, prefix, sources = sys.argv[1], sys.argv[2], sys.argv[3:]
    chparam = os.environ.get("YOSYS_CHPARAM", "")
    netlist, log = prefix + ".v", prefix + ".log"
    script = "read_verilog -sv -DSYNTHESIS " + " ".join(sources) + "; "
    if chparam:
        script += "chparam " + chparam + " shade_unit; "
    script += "synth -flatten -top shade_unit; opt_clean; write_verilog -noattr " + netlist
    if yosys != "-":  # "-": check OUT_PREFIX.v as it is (the checker's own test)
        subprocess.run([yosys, "-q", "-l", log, "-p", script], check=True,
                       stdout=subprocess.DEVNULL)
    text = open(netlist).read()
    port_re = re.compile(r"\b(" + "|".join(PORTS) + r")\b")
    widths = {}
    for m in re.finditer(r"output\s+(?:\[(\d+):0\]\s+)?(\w+)\s*;", text):
        if m.group(2) in PORTS:
            widths[m.group(2)] = int(m.group(1) or 0) + 1
    missing = [p for p in PORTS if p not in widths]
    if missing:
        sys.exit(f"yosys_outputs_check: no output {missing} in {netlist}")
    # A port driven whole by the flattened register of the same name in a submodule
    # (`assign pix_x_o = \u_out_reg.pix_x_o ;`): that register's bits are the port's.
    reg_of = {p: p for p in PORTS}
    for m in re.finditer(r"^\s*assign\s+(\w+)\s*=\s*(\\\S+)\s*;\s*$", text, re.M):
        if m.group(1) in PORTS and m.group(2).endswith("." + m.group(1)):
            reg_of[m.group(1)] = m.group(2)
    bad = []
    for m in re.finditer(r"^\s*assign\s+(.*?)\s*=\s*(.*?);\s*$", text, re.M):
        lhs, rhs = m.group(1), m.group(2)
        if not port_re.search(lhs) or (lhs in PORTS and rhs.strip() == reg_of[lhs]):
            continue
        # Constants ('h, 'b, 'd, 'x literals) or other output bits on the right: the output is
        # not its own register.
        if re.search(r"\d+'[hbdo]", rhs) or port_re.search(rhs):
            bad.append(m.group(0).strip())
    # Every output bit must be a flip-flop's output: count the distinct output bits assigned in
    # always blocks (`pix_colour_o[3] <=`) or through a register (`assign pix_colour_o[3] =
    # \pix_colour_o_reg[3]`).
    for port, width in widths.items():
        reg = re.escape(reg_of[port]) + r"\s*" if reg_of[port] != port else r"\b" + port
        regs = set(re.findall(reg + r"\[(\d+)\]\s*<=", text))
        for hi, lo in re.findall(reg + r"\[(\d+):(\d+)\]\s*<=", text):
            regs |= {str(b) for b in range(int(lo), int(hi) + 1)}
        if re.search(reg + r"\s*<=", text):
            regs |= {str(b) for b in range(width)}
        regs |= set(re.findall(r"assign\s+" + port + r"\[(\d+)\]\s*=\s*\\" + port +
                               r"_reg\[\d+\]\s*;", text))
        if len(regs) != width:
            bad.append(f"{port}: {len(regs)} of {width} bits are their own flip-flop")
    if bad:
        print(f"yosys_outputs_check: constant or aliased pixel outputs in {netlist}:")
        for b in bad:
            print("  " + (b if len(b) < 300 else b[:300] + " ..."))
        sys.exit(1)
    cells = re.findall(r"Number of cells:\s+(\d+)", open(log).read()) if os.path.exists(log) else []
    print(f"yosys_outputs_check: every bit of {', '.join(PORTS)} is its own flip-flop"
          + (f" ({cells[-1]} cells)" if cells else ""))


if __name__ == "__main__":
    main()
