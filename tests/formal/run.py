#!/usr/bin/env python3
"""Formal checks of shade_unit (docs/formal.md): tests/formal/shade_formal.sv on one small
configuration. Yosys builds the model (AIGER and RTLIL); then

  run.py CONFIG --mode prove              ABC's pdr: PROVEN means for all time (unbounded)
  run.py CONFIG --mode bmc --depth N      Yosys sat: N cycles from reset (bounded, not a proof)
  --check protocol | conservation         the port and queue properties (default), or those
                                          and the span scoreboard with END_FRAME

--rtl DIR reads the RTL from DIR (a deliberately broken copy, tests/formal/broken.sh) instead of
rtl/, --wrapper FILE another copy of shade_formal.sv. --expect-fail inverts the verdict: the
check must fail, with its counterexample as VCD (and --expect-assert NAME: NAME among the
assertions that fail in it).
Prints one line per step with its time; exits 0 when the verdict is what was asked for.
"""
import argparse
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def slots(*values):
    """SPEC_PARAMS: slot k (32 bits) at [k*32 +: 32], as a Verilog literal."""
    v = sum(x << (32 * k) for k, x in enumerate(values))
    return f"256'h{v:064x}"


# One configuration per specular kind; between them lanes 1 and 2, queue 1 and 2, both material
# buffer counts and both slot timings (pipelined, iterative). Each unit's own fields are the
# smallest its range checks accept around the wrapper's 6-bit series (2 integer bits).
CONFIGS = {
    "ideal_l1_q1": dict(SPECULAR_KIND=0, LANES=1, TRI_QUEUE=1),
    # lut: addr_bits 2, entry_bits 3, no interpolation, truncating index: latency 2
    "lut_l2_q2": dict(SPECULAR_KIND=1, LANES=2, TRI_QUEUE=2, SPEC_PARAMS=slots(2, 3, 0, 0)),
    # schlick: quotient_bits 3, operand_bits 3, pipelined: latency 3
    "schlick_l1_q1": dict(SPECULAR_KIND=2, LANES=1, TRI_QUEUE=1, SPEC_PARAMS=slots(3, 3, 0)),
    # pdr: 65 s alone, 222 s under load (docs/formal.md): not in the ctests
    "schlick_l1_q2": dict(SPECULAR_KIND=2, LANES=1, TRI_QUEUE=2, SPEC_PARAMS=slots(3, 3, 0)),
    # wpow: max_m 4, base_bits 3, iterative: 3 cycles a pixel
    "wpow_l2_q1_mb2": dict(SPECULAR_KIND=3, LANES=2, TRI_QUEUE=1, MATERIAL_BUFFERS=2,
                           SPEC_PARAMS=slots(4, 3, 1)),
    "none_l2_q1": dict(SPECULAR_KIND=4, LANES=2, TRI_QUEUE=1),
    # pdr undecided after 10 minutes (docs/formal.md): not in the ctests
    "none_l1_q2_mb2": dict(SPECULAR_KIND=4, LANES=1, TRI_QUEUE=2, MATERIAL_BUFFERS=2),
}

# Probe (shade_formal's p_* wire) -> shade_unit's signal, after flatten. u = the wrapper's DUT.
PROBES = {
    "p_hdr_fire": "u_dut.hdr_fire",
    "p_pay_fire": "u_dut.u_decoder.u_payload.pay_fire",
    "p_item_n": "u_dut.u_decoder.item_n",
    "p_beat_left": "u_dut.u_decoder.beat_left",
    "p_span_fire": "u_dut.span_fire",
    "p_tri_fire": "u_dut.tri_fire",
    "p_tri_bank_free": "u_dut.tri_bank_free",
    "p_s1_load": "u_dut.s1_load",
    "p_s1_free": "u_dut.s1_free",
    "p_s1_v": "u_dut.u_span_source.g_unit_setup.u_setup_ctrl.s1_v_q",
    "p_s2_v": "u_dut.u_span_source.g_unit_setup.u_setup_ctrl.s2_v_q",
    "p_s3_v": "u_dut.u_span_source.g_unit_setup.u_setup_ctrl.s3_v_q",
    "p_eng_load": "u_dut.load_eng",
    "p_run": "u_dut.run",
    "p_rem": "u_dut.u_engine_ctrl.rem_q",
    "p_out_load": "u_dut.u_out_reg.load_i",
    "p_out_adv": "u_dut.adv",
    "p_datapath_empty": "u_dut.datapath_empty",
}
SQ = "u_dut.u_span_source.g_unit_setup.u_span_queue.g_span_queue."
PROBES_SQ = {
    "g_sq.p_count": SQ + "count_q",
    "g_sq.p_head": SQ + "head_q",
    "g_sq.p_tail": SQ + "tail_q",
    "g_sq.p_bank0": SQ + "bank_spans_q[0]",
    "g_sq.p_bank1": SQ + "bank_spans_q[1]",
}
MB = "u_dut.u_material_bank."
PROBES_MB = {
    "g_mb.p_spans0": MB + "g_mat_banks.mat_spans_q[0]",
    "g_mb.p_spans1": MB + "g_mat_banks.mat_spans_q[1]",
    "g_mb.p_leave": MB + "leave_i",
    "g_mb.p_leave_bank": MB + "leave_bank_i",
}


def rtl_files(rtl_dir):
    """shade_unit's sources in order, from the one list rtl/files.f (cmake/rtl_files.cmake)."""
    names = []
    with open(os.path.join(ROOT, "rtl", "files.f")) as f:
        for line in f:
            line = line.strip()
            if line and not line.startswith("//"):
                names.append(os.path.join(rtl_dir, line))
    return names


def yosys_script(cfg, rtl_dir, conserve, work, wrapper):
    params = dict(cfg)
    params["CONSERVE"] = 1 if conserve else 0
    probes = dict(PROBES)
    if cfg.get("TRI_QUEUE", 1) > 1:
        probes.update(PROBES_SQ)
    if cfg.get("MATERIAL_BUFFERS", 1) == 2:
        probes.update(PROBES_MB)
    # SYNTHESIS: the RTL's simulation-only code (plusargs, $fatal range checks) is left out,
    # as for every other Yosys run; read_verilog -formal does not define it.
    lines = ["read_verilog -sv -formal -DSYNTHESIS " + " ".join(rtl_files(rtl_dir)),
             "read_verilog -sv -formal " + wrapper]
    lines += [f"chparam -set {k} {v} shade_formal" for k, v in params.items()]
    lines += ["hierarchy -check -top shade_formal", "proc", "flatten"]
    # Backslash names: flatten keeps the child's wires as `\u_dut.<path>`.
    lines += [f"connect -set \\{p} \\{s}" for p, s in probes.items()]
    # The colours are cut at the pix register's input (a free value each cycle): the checks are
    # about control and hold for any colour, and the datapath (series, specular arithmetic,
    # coefficient and material registers) leaves the model. Iterative units' busy stays.
    lines += ["cutpoint w:u_dut.colour_out"]
    # `check -assert`: a probe left undriven (a renamed signal) stops the run here.
    lines += ["opt_clean", "check -assert", "memory_map", "opt -fast", "async2sync",
              f"write_rtlil {work}/model.il",
              # SymbiYosys's AIGER preparation, for ABC's pdr and bmc3.
              "setattr -unset keep", "delete -output", "opt -full", "techmap", "opt -fast",
              "dffunmap", "abc -g AND -fast", "opt_clean",
              f"write_aiger -I -B -zinit -map {work}/model.aim {work}/model.aig"]
    return "\n".join(lines) + "\n"


def run(cmd, log):
    t0 = time.time()
    with open(log, "w") as f:
        rc = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT).returncode
    with open(log) as f:
        text = f.read()
    return rc, text, time.time() - t0


def counterexample(work, frame):
    """The failing trace as VCD: Yosys replays ABC's witness on the model before AIGER."""
    vcd = os.path.join(work, "cex.vcd")
    # The colour cut point ($anyseq) is not in the witness Yosys sim reads: left alone it is x,
    # and every comparison of a colour with x "fails". Colour 0 instead: a failure the replay
    # names is then never one of the colour alone.
    script = (f"read_rtlil {work}/model.il; delete t:$anyseq; setundef -undriven -zero; "
              f"sim -clock clk_i -r {work}/trace.aiw "
              f"-map {work}/model.aim -n {frame + 1} -vcd {vcd} shade_formal")
    rc, text, _ = run(["yosys", "-p", script], os.path.join(work, "cex.log"))
    failed = sorted(set(re.findall(r"Assert (\S+) \(.*?\) failed", text)))
    return (vcd if rc == 0 and os.path.exists(vcd) else None), failed


def bmc(a, tag, work):
    """Yosys's own SAT solver, unrolled a.depth cycles from reset (ABC's bmc3 and z3 did not
    reach a useful depth on this model in minutes: docs/formal.md)."""
    vcd = os.path.join(work, "cex.vcd")
    script = (f"read_rtlil {work}/model.il; sat -seq {a.depth} -prove-asserts -set-assumes "
              f"-show-ports -dump_vcd {vcd}")
    rc, text, secs = run(["yosys", "-p", script], os.path.join(work, "sat.log"))
    if "no model found: SUCCESS" in text:
        verdict = f"PASSED (bounded: BMC to depth {a.depth}, not a proof)"
    elif "model found: FAIL" in text:
        verdict = "FAILED"
    else:
        verdict = f"ERROR (rc {rc})"
    print(f"{tag}: sat -seq {a.depth}: {verdict} in {secs:.1f} s")
    if verdict == "FAILED":
        print(f"  counterexample: {vcd}")
    if a.expect_fail:
        return 0 if verdict == "FAILED" and os.path.exists(vcd) else 1
    return 0 if verdict.startswith("PASSED") else 1


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("config", choices=sorted(CONFIGS))
    ap.add_argument("--mode", choices=["prove", "bmc"], required=True)
    ap.add_argument("--check", choices=["protocol", "conservation"], default="protocol")
    ap.add_argument("--depth", type=int, default=12, help="bmc: cycles from reset")
    ap.add_argument("--rtl", default=os.path.join(ROOT, "rtl"))
    ap.add_argument("--work", default=None, help="output folder")
    ap.add_argument("--wrapper", default=os.path.join(HERE, "shade_formal.sv"))
    ap.add_argument("--expect-fail", action="store_true")
    ap.add_argument("--expect-assert", default=None,
                    help="with --expect-fail: this assertion must be among the failing ones")
    a = ap.parse_args()

    tag = f"{a.config}_{a.check}_{a.mode}"
    work = os.path.abspath(a.work or f"formal_{tag}")
    os.makedirs(work, exist_ok=True)
    ys = os.path.join(work, "model.ys")
    with open(ys, "w") as f:
        f.write(yosys_script(CONFIGS[a.config], a.rtl, a.check == "conservation", work,
                             a.wrapper))
    rc, text, secs = run(["yosys", "-q", "-s", ys], os.path.join(work, "yosys.log"))
    print(f"{tag}: yosys {secs:.1f} s")
    if rc != 0:
        print(text[-3000:])
        return 2

    if a.mode == "bmc":
        return bmc(a, tag, work)
    abc = f"read_aiger {work}/model.aig; fold; strash; pdr; write_cex -a {work}/trace.aiw"
    rc, text, secs = run(["yosys-abc", "-c", abc], os.path.join(work, "abc.log"))
    m = re.search(r"asserted in frame (\d+)", text)
    if m:
        verdict, frame = "FAILED", int(m.group(1))
    elif "Property proved" in text:
        verdict = "PROVEN (unbounded, pdr)"
    else:
        print(text[-2000:])
        verdict = "UNDECIDED"
    print(f"{tag}: pdr: {verdict} in {secs:.1f} s")
    if verdict == "FAILED":
        vcd, failed = counterexample(work, frame)
        print(f"  failing at cycle {frame}: {' '.join(failed) or '(assertion names: see cex.log)'}")
        print(f"  counterexample: {vcd or 'NOT WRITTEN (see cex.log)'}")
        if a.expect_fail:
            named = a.expect_assert is None or f"shade_formal.{a.expect_assert}" in failed
            ok = vcd is not None and named
            print(f"{tag}: failed as required" + ("" if vcd else ", but no counterexample") +
                  ("" if named else f", but not by {a.expect_assert}"))
            return 0 if ok else 1
        return 1
    if a.expect_fail:
        print(f"{tag}: {verdict}, but it must fail")
        return 1
    return 0 if verdict != "UNDECIDED" else 1


if __name__ == "__main__":
    sys.exit(main())
