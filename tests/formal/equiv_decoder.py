#!/usr/bin/env python3
"""Sequential equivalence of the command decoder with its pre-issue-44 form (docs/rtl.md, "The
command decoder's structure"): rtl/cmd_decoder.sv with its payload FSM (rtl/cmd_payload.sv), and
with host span setup also rtl/start_bank.sv, against the copies of commit 56aaa48 kept in
tests/data/decoder_ref/ (verbatim; their modules are renamed ref_* as they are read), on one
configuration.

Both designs are wrapped alike (eq_side_ref, eq_side_new): reset in the first cycle, every input
free from then on (cmd_data_i, cmd_valid_i, every *_i condition, resets; no stream contract is
assumed), and with host setup the start bank in the loop as shade_unit has it (its free_o is the
decoder's start_free_i; the engines' load_i and the material bank a free input). Yosys builds the
miter (`miter -equiv`: every output of the two, bit for bit, every cycle; hdr_n_o in the cycles a
header is taken, hdr_fire_o, the only ones its readers look at it: coef_bank, span_queue,
material_bank and start_bank read it under tri_fire_o / span_fire_o) and ABC's pdr proves that no
input sequence from reset ever makes them differ: unbounded, for all time.

  equiv_decoder.py CONFIG [--work DIR]       PROVEN, or FAILED with the cycle of the first
                                             difference (and a VCD of it), exit 0 only if proven
  --rtl DIR                                  the new side from DIR instead of rtl/
  --break FILE:OLD:NEW                       a copy of rtl/ with OLD replaced by NEW in FILE (once,
                                             or the check errs) as the new side
  --expect-fail                              exit 0 only if the check fails (with a VCD)
  --list                                     the configurations
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
REF = os.path.join(ROOT, "tests", "data", "decoder_ref")
REF_MODULES = ("cmd_decoder", "cmd_payload", "start_bank")
WORD = 64

# The shipped scenes' own units (shadesim config SCENE; the cmd_decoder and start_bank
# parameters shade_unit derives from them: START_WORDS = start_words(series, series_wl),
# N_MAT_FIXED = channels + (1 or 2) x colours), then the other structures the decoder has:
# one- and eight-word ports, unit span setup with and without a span queue, two material buffers.
CONFIGS = {
    # name: PORT_WORDS, QUEUED, MAT_BANKED, N_MAT_FIXED, HOST_SETUP, START_WORDS,
    #       start bank (host): N_SER, SERIES_WL, XY_BITS, DEPTH
    "multi": dict(PW=4, Q=0, MB=0, NMF=15, HOST=1, SW=6, NSER=4, SWL=29, XY=9, DEPTH=2),
    "specular": dict(PW=4, Q=0, MB=0, NMF=2, HOST=1, SW=3, NSER=2, SWL=23, XY=8, DEPTH=2),
    "sphere": dict(PW=2, Q=0, MB=0, NMF=2, HOST=1, SW=1, NSER=1, SWL=16, XY=8, DEPTH=1),
    "torus": dict(PW=2, Q=0, MB=0, NMF=2, HOST=1, SW=3, NSER=2, SWL=23, XY=9, DEPTH=2),
    "suzanne": dict(PW=4, Q=0, MB=0, NMF=2, HOST=1, SW=3, NSER=2, SWL=23, XY=9, DEPTH=2),
    "p1_unit": dict(PW=1, Q=0, MB=0, NMF=2, HOST=0, SW=1),
    "p1_host": dict(PW=1, Q=0, MB=1, NMF=2, HOST=1, SW=3, NSER=2, SWL=23, XY=6, DEPTH=2),
    "p2_queued_mb2": dict(PW=2, Q=1, MB=1, NMF=4, HOST=0, SW=1),
    "p4_unit_mb2": dict(PW=4, Q=0, MB=1, NMF=2, HOST=0, SW=1),
    "p4_queued": dict(PW=4, Q=1, MB=0, NMF=2, HOST=0, SW=1),
    "p8_queued_mb2": dict(PW=8, Q=1, MB=1, NMF=7, HOST=0, SW=1),
    "p8_host": dict(PW=8, Q=0, MB=0, NMF=2, HOST=1, SW=12, NSER=4, SWL=62, XY=6, DEPTH=2),
    "p8_host_short": dict(PW=8, Q=0, MB=1, NMF=2, HOST=1, SW=3, NSER=2, SWL=23, XY=6, DEPTH=1),
}


def ref_text(name):
    """A reference copy with its modules renamed ref_<name> (definitions and instances)."""
    with open(os.path.join(REF, name + ".sv")) as f:
        text = f.read()
    for m in REF_MODULES:
        text = re.sub(r"\b%s\b(?=\s*(#|\())" % m, "ref_" + m, text)
        text = re.sub(r"^module %s\b" % m, "module ref_" + m, text, flags=re.M)
    return text


def side(cfg, prefix, tag):
    """One side of the miter: the decoder (and start bank) of `prefix`, reset in cycle 0."""
    pw, host = cfg["PW"], cfg["HOST"]
    nw = (pw).bit_length()  # $clog2(PW + 1) for PW = 1, 2, 4, 8
    posw = max(1, (pw - 1).bit_length())
    dec = (f"{prefix}cmd_decoder #(.PORT_WORDS({pw}), .QUEUED(1'b{cfg['Q']}), "
           f".MAT_BANKED(1'b{cfg['MB']}), .N_MAT_FIXED({cfg['NMF']}), .HOST_SETUP(1'b{host}), "
           f".START_WORDS({cfg['SW']}))")
    ports = [
        "input logic clk_i", "input logic rst_ni",
        f"input logic [{pw * WORD - 1}:0] cmd_data_i", "input logic cmd_valid_i",
        "input logic datapath_empty_i", "input logic mat_other_free_i",
        "input logic mat_cur_free_i", "input logic sq_full_i", "input logic [15:0] sq_room_i",
        "input logic s1_free_i", "input logic tri_bank_free_i",
        "output logic cmd_ready_o", f"output logic [{WORD - 1}:0] word_o",
        f"output logic [{posw - 1}:0] word_sel_o", "output logic [7:0] hdr_op_o",
        f"output logic [{nw - 1}:0] hdr_pos_o", f"output logic [{nw - 1}:0] hdr_n_fired_o",
        "output logic hdr_fire_o", "output logic span_fire_o", "output logic tri_fire_o",
        "output logic mat_fire_o", f"output logic [{nw - 1}:0] tail_n_o",
        "output logic [15:0] pay_idx_o", "output logic span_pay_o", "output logic pay_mat_o",
        "output logic cfg_valid_o", "output logic cfg_table_o", "output logic cfg_all_banks_o",
        "output logic [15:0] cfg_addr_o"]
    body = ["  logic started_q = 1'b0;  // reset in the first cycle",
            "  always_ff @(posedge clk_i) started_q <= 1'b1;",
            "  logic rst_n;",
            "  assign rst_n = rst_ni && started_q;",
            f"  logic [{nw - 1}:0] hdr_n_o;  // read only with a header taken",
            "  assign hdr_n_fired_o = hdr_fire_o ? hdr_n_o : '0;"]
    conns = ("    .clk_i, .rst_ni(rst_n), .cmd_data_i, .cmd_valid_i, .datapath_empty_i,\n"
             "    .mat_other_free_i, .mat_cur_free_i, .sq_full_i, .sq_room_i, .s1_free_i,\n"
             "    .tri_bank_free_i, .start_free_i, .cmd_ready_o, .word_o, .word_sel_o,\n"
             "    .hdr_op_o, .hdr_pos_o, .hdr_n_o, .hdr_fire_o, .span_fire_o, .tri_fire_o,\n"
             "    .mat_fire_o, .tail_n_o, .pay_idx_o, .span_pay_o, .pay_mat_o, .cfg_valid_o,\n"
             "    .cfg_table_o, .cfg_all_banks_o, .cfg_addr_o")
    if host:
        nser, swl, xy = cfg["NSER"], cfg["SWL"], cfg["XY"]
        ports += ["input logic mat_i", "input logic load_i",
                  "output logic start_free_o", "output logic valid_o", "output logic empty_o",
                  f"output logic [{3 * xy + 1}:0] span_o", "output logic mat_o",
                  f"output logic [{nser * swl - 1}:0] v_o",
                  f"output logic [{nser * swl - 1}:0] d_o",
                  f"output logic [{nser * swl - 1}:0] d2_o"]
        body += ["  logic start_free_i;",
                 "  assign start_free_o = start_free_i;",
                 f"  {dec} u_dec (\n{conns}\n  );",
                 f"  {prefix}start_bank #(.PORT_WORDS({pw}), .N_SER({nser}), .SERIES_WL({swl}), "
                 f".XY_BITS({xy}), .DEPTH({cfg['DEPTH']})) u_bank (\n"
                 "    .clk_i, .rst_ni(rst_n), .cmd_valid_i, .cmd_data_i, .hdr_i(word_o),\n"
                 "    .span_fire_i(span_fire_o), .mat_i, .tail_n_i(tail_n_o),\n"
                 "    .pay_idx_i(pay_idx_o), .hdr_pos_i(hdr_pos_o), .hdr_n_i(hdr_n_o),\n"
                 "    .filling_i(span_pay_o), .load_i, .free_o(start_free_i), .valid_o,\n"
                 "    .empty_o, .span_o, .mat_o, .v_o, .d_o, .d2_o\n"
                 "  );"]
    else:
        ports += ["input logic start_free_i"]
        body += [f"  {dec} u_dec (\n{conns}\n  );"]
    return (f"module eq_side_{tag} (\n  " + ",\n  ".join(ports) + "\n);\n" + "\n".join(body) +
            "\nendmodule\n")


def run(cmd, log, timeout=None):
    t0 = time.time()
    with open(log, "w") as f:
        try:
            rc = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT, timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            rc = -1
    with open(log) as f:
        text = f.read()
    return rc, text, time.time() - t0


def broken_copy(spec, work):
    """rtl/ copied to work/rtl with one replacement (FILE:OLD:NEW): the check must catch it."""
    fname, old, new = spec.split(":", 2)
    dst = os.path.join(work, "rtl")
    shutil.rmtree(dst, ignore_errors=True)
    shutil.copytree(os.path.join(ROOT, "rtl"), dst)
    path = os.path.join(dst, fname)
    with open(path) as f:
        text = f.read()
    if text.count(old) != 1:
        sys.exit(f"--break: {old!r} occurs {text.count(old)} times in rtl/{fname}, not once")
    with open(path, "w") as f:
        f.write(text.replace(old, new))
    return dst


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("config", nargs="?", choices=sorted(CONFIGS))
    ap.add_argument("--work", default=None)
    ap.add_argument("--rtl", default=os.path.join(ROOT, "rtl"))
    ap.add_argument("--break", dest="brk", default=None, metavar="FILE:OLD:NEW")
    ap.add_argument("--expect-fail", action="store_true")
    ap.add_argument("--timeout", type=int, default=900, help="seconds for pdr (default 900)")
    ap.add_argument("--list", action="store_true")
    a = ap.parse_args()
    if a.list or not a.config:
        for name, cfg in CONFIGS.items():
            print(name, " ".join(f"{k}={v}" for k, v in cfg.items()))
        return 0
    cfg = CONFIGS[a.config]
    tag = f"equiv_decoder_{a.config}"
    work = os.path.abspath(a.work or tag)
    os.makedirs(work, exist_ok=True)
    rtl = broken_copy(a.brk, work) if a.brk else os.path.abspath(a.rtl)

    mods = ["cmd_payload", "cmd_decoder"] + (["start_bank"] if cfg["HOST"] else [])
    ref_file = os.path.join(work, "ref.sv")
    with open(ref_file, "w") as f:
        f.write("".join(ref_text(m) for m in mods))
    wrap = os.path.join(work, "wrap.sv")
    with open(wrap, "w") as f:
        f.write(side(cfg, "ref_", "ref") + side(cfg, "", "new"))
    # The new side's leaves: the package and the one-hot pick the three modules share.
    new_files = " ".join(os.path.join(rtl, m + ".sv")
                         for m in ["shade_pkg", "onehot_mux"] + mods)
    ys = "\n".join([
        # SYNTHESIS: no $fatal range checks, no SVA (as every Yosys run of rtl/ reads it).
        f"read_verilog -sv -DSYNTHESIS {new_files}",
        f"read_verilog -sv -DSYNTHESIS {ref_file}",
        f"read_verilog -sv {wrap}",
        "hierarchy -check", "proc", "flatten", "opt_clean", "memory -nomap", "memory_map",
        "opt -fast", "async2sync",
        # Registers without a reset (the start bank's words) start alike on both sides.
        "setundef -undriven -zero", "setundef -init -zero",
        "miter -equiv -flatten -make_assert eq_side_ref eq_side_new miter",
        "hierarchy -top miter", f"write_rtlil {work}/miter.il",
        "setattr -unset keep", "delete -output", "opt -full", "techmap", "opt -fast",
        "dffunmap", "abc -g AND -fast", "opt_clean", "stat",
        f"write_aiger -I -B -zinit -map {work}/miter.aim {work}/miter.aig"]) + "\n"
    with open(os.path.join(work, "miter.ys"), "w") as f:
        f.write(ys)
    rc, text, secs = run(["yosys", "-q", "-s", os.path.join(work, "miter.ys")],
                         os.path.join(work, "yosys.log"))
    if rc != 0:
        print(text[-3000:])
        print(f"{tag}: yosys failed ({rc})")
        return 2
    print(f"{tag}: yosys {secs:.1f} s")

    abc = f"read_aiger {work}/miter.aig; fold; strash; pdr; write_cex -a {work}/trace.aiw"
    rc, text, secs = run(["yosys-abc", "-c", abc], os.path.join(work, "abc.log"), a.timeout)
    m = re.search(r"asserted in frame (\d+)", text)
    if m:
        verdict = "FAILED"
    elif "Property proved" in text:
        verdict = "PROVEN (unbounded, pdr)"
    else:
        print(text[-2000:])
        verdict = "UNDECIDED" + (" (timeout)" if rc == -1 else "")
    print(f"{tag}: pdr: {verdict} in {secs:.1f} s")
    if verdict == "FAILED":
        frame = int(m.group(1))
        vcd = os.path.join(work, "cex.vcd")
        script = (f"read_rtlil {work}/miter.il; sim -clock in_clk_i -r {work}/trace.aiw "
                  f"-map {work}/miter.aim -n {frame + 1} -vcd {vcd} miter")
        run(["yosys", "-p", script], os.path.join(work, "cex.log"))
        print(f"  the outputs differ in cycle {frame} from reset; counterexample: "
              f"{vcd if os.path.exists(vcd) else 'NOT WRITTEN (see cex.log)'}")
        if a.expect_fail:
            ok = os.path.exists(vcd)
            print(f"{tag}: failed as required" + ("" if ok else ", but no counterexample"))
            return 0 if ok else 1
        return 1
    if a.expect_fail:
        print(f"{tag}: {verdict}, but it must fail")
        return 1
    return 0 if verdict.startswith("PROVEN") else 1


if __name__ == "__main__":
    sys.exit(main())
