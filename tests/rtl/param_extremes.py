#!/usr/bin/python3
"""Every parameter check of rtl/ at its edges: shade_unit elaborated by Icarus at each
legal extreme must run its time-0 checks without a $fatal, and one step past it must stop with
that check's own message.

  param_extremes.py SHADESIM IVERILOG VVP SOURCE_DIR WORK

A legal extreme is a UnitConfig (the model's ranges, model/unit_config.cpp and
model/specular_units.cpp) mapped to Verilog parameters by the one mapping (`shadesim rtl-params
--tool iverilog`); a case past the edge overrides one Verilog parameter of a legal unit, since
the model itself refuses such a unit. The RTL read is $SHADESIM_RTL_DIR when set (a mutant's
copy, scripts/mutate-rtl), else SOURCE_DIR/rtl. Exit 0 only when every case behaves.

The specular units' own fields are packed into SPEC_PARAMS by slot (model/specular_units.cpp);
a case past one of their edges overrides one slot ("SPEC_PARAMS[k]") of a legal unit's literal.
Left out: checks that only a build with a TABLE_FILE reaches.
"""
import json
import os
import re
import subprocess
import sys
import tempfile

def or_zero_width(module):
    """A regex alternative: Icarus refusing the module's zero-width vector or cast while
    elaborating (before any time-0 check runs); the compile error names the module."""
    return rf"|{module}\.sv:\d+: error: (Cast size|Indexed part widths)"


# name, UnitConfig overlay (JSON), Verilog overrides {NAME: value} ("SPEC_PARAMS[k]" sets slot k),
# expected: None (elaborates and passes its checks) or a regex of the $fatal message.
LUT = {"kind": "lut"}


WPOW = {"kind": "wpow"}
SCHLICK = {"kind": "schlick"}
HOST_S2_1 = {"span_setup": "host", "series": "s2.1:wrap", "out_bits": 1}
CASES = [
    ("tri_queue_8", {"tri_queue": 8}, {}, None),
    ("tri_queue_9", {"tri_queue": 8}, {"TRI_QUEUE": 9}, r"coef_bank: TRI_QUEUE 9 is not 1\.\.8"),
    ("xy_bits_4", {"xy_bits": 4, "offset_bits": 6}, {}, None),
    ("xy_bits_3", {"xy_bits": 4, "offset_bits": 6}, {"XY_BITS": 3}, r"XY_BITS 3 is not 4\.\.15"),
    ("xy_bits_15", {"xy_bits": 15}, {}, None),
    ("xy_bits_16", {"xy_bits": 15}, {"XY_BITS": 16}, r"XY_BITS 16 is not 4\.\.15"),
    ("lanes_4", {"lanes": 4}, {}, None),
    ("lanes_3", {"lanes": 4}, {"LANES": 3}, r"LANES 3 is not 1, 2 or 4"),
    ("lights_8", {"lights": 8}, {}, None),
    ("lights_9", {"lights": 8}, {"LIGHTS": 9}, r"LIGHTS 9 is not 1\.\.8"),
    ("channels_3", {"channels": 3}, {}, None),
    ("channels_2", {"channels": 3}, {"CHANNELS": 2}, r"CHANNELS 2 is not 1 or 3"),
    ("material_buffers_2", {"material_buffers": 2}, {}, None),
    ("material_buffers_3", {"material_buffers": 2}, {"MATERIAL_BUFFERS": 3},
     r"MATERIAL_BUFFERS 3 is not 1 or 2"),
    ("span_setup_host", {"span_setup": "host"}, {}, None),
    ("span_setup_2", {"span_setup": "host"}, {"SPAN_SETUP": 2}, r"SPAN_SETUP 2 is not 0"),
    ("start_depth_1", {"span_setup": "host", "start_depth": 1}, {}, None),
    ("start_depth_2", {"span_setup": "host", "start_depth": 2}, {}, None),
    ("start_depth_0", {"span_setup": "host", "start_depth": 1}, {"START_DEPTH": 0},
     r"start_bank: DEPTH 0 is not 1 or 2" + or_zero_width("start_bank")),
    ("start_depth_3", {"span_setup": "host", "start_depth": 2}, {"START_DEPTH": 3},
     r"start_bank: DEPTH 3 is not 1 or 2"),
    # The start bank's series: one (grey, one light, no specular) and the model's widths.
    ("start_bank_one_series", {"span_setup": "host", "specular": {"kind": "none"}}, {}, None),
    ("start_bank_series_wl_3", HOST_S2_1, {}, None),
    ("start_bank_series_wl_2", HOST_S2_1, {"SERIES_WL": 2},
     r"start_bank: N_SER 2 or SERIES_WL 2 out of range"),
    ("start_bank_series_wl_62", {"span_setup": "host", "series": "s4.58:wrap"}, {}, None),
    ("start_bank_series_wl_63", {"span_setup": "host", "series": "s4.58:wrap"}, {"SERIES_WL": 63},
     r"start_bank: N_SER 2 or SERIES_WL 63 out of range"),
    ("diffuse_multiply_2", {}, {"DIFFUSE_MULTIPLY": 2}, r"DIFFUSE_MULTIPLY 2 is not 0 or 1"),
    ("offset_bits_2", {"offset_bits": 2, "xy_bits": 4}, {}, None),
    ("offset_bits_1", {"offset_bits": 2, "xy_bits": 4}, {"OFS_BITS": 1},
     r"series_path: OFS_BITS 1 is not 2\.\.17"),
    ("offset_bits_18", {}, {"OFS_BITS": 18}, r"series_path: OFS_BITS 18 is not 2\.\.17"),
    ("specular_kind_none", {"specular": {"kind": "none"}}, {}, None),
    ("specular_kind_5", {"specular": {"kind": "none"}}, {"SPECULAR_KIND": 5},
     r"spec_slots: SPECULAR_KIND 5 is not 0 ideal"),
    ("coef_term_2", {}, {"COEF_T1_WL": 2}, None),
    ("coef_term_1", {}, {"COEF_T1_WL": 1}, r"COEF_T1_WL must be 2\.\.COEF_WL"),
    # The specular units' slots (exponent_lut.sv, wpow_unit.sv, schlick_divider.sv).
    ("lut_addr_bits_1", {"specular": {**LUT, "lut": {"addr_bits": 1}}}, {}, None),
    # A zero width stops Icarus's elaboration before the time-0 check runs (or_zero_width).
    ("lut_addr_bits_0", {"specular": {**LUT, "lut": {"addr_bits": 1}}}, {"SPEC_PARAMS[0]": 0},
     r"exponent_lut: ADDR_BITS 0 is not 1\.\.16" + or_zero_width("exponent_lut")),
    ("lut_addr_bits_16", {"specular": {**LUT, "lut": {"addr_bits": 16}}}, {}, None),
    ("lut_addr_bits_17", {"specular": {**LUT, "lut": {"addr_bits": 16}}}, {"SPEC_PARAMS[0]": 17},
     r"exponent_lut: ADDR_BITS 17 is not 1\.\.16"),
    ("lut_entry_bits_1", {"specular": {**LUT, "lut": {"entry_bits": 1}}}, {}, None),
    ("lut_entry_bits_0", {"specular": {**LUT, "lut": {"entry_bits": 1}}}, {"SPEC_PARAMS[1]": 0},
     r"exponent_lut: ENTRY_BITS 0 is not >= 1" + or_zero_width("exponent_lut")),
    ("lut_index_1", {"specular": {**LUT, "lut": {"index": "nearest"}}}, {}, None),
    ("lut_index_2", {"specular": {**LUT, "lut": {"index": "nearest"}}}, {"SPEC_PARAMS[3]": 2},
     r"exponent_lut: INDEX 2 is not 0 or 1"),
    ("wpow_max_m_1", {"specular": {**WPOW, "wpow": {"max_m": 1}}}, {}, None),
    ("wpow_max_m_0", {"specular": {**WPOW, "wpow": {"max_m": 1}}}, {"SPEC_PARAMS[0]": 0},
     r"wpow_unit: MAX_M must be a power of two, got 0"),
    ("wpow_max_m_32", {"specular": {**WPOW, "wpow": {"max_m": 32}}}, {}, None),
    ("wpow_max_m_3", {"specular": {**WPOW, "wpow": {"max_m": 32}}}, {"SPEC_PARAMS[0]": 3},
     r"wpow_unit: MAX_M must be a power of two, got 3"),
    ("wpow_base_bits_2", {"specular": {**WPOW, "wpow": {"base_bits": 2}}}, {}, None),
    ("wpow_base_bits_1", {"specular": {**WPOW, "wpow": {"base_bits": 2}}}, {"SPEC_PARAMS[1]": 1},
     r"wpow_unit: BASE_BITS 1 < 2"),
    ("wpow_timing_1", {"specular": {**WPOW, "wpow": {"timing": "iterative"}}}, {}, None),
    ("wpow_timing_2", {"specular": {**WPOW, "wpow": {"timing": "iterative"}}},
     {"SPEC_PARAMS[2]": 2}, r"wpow_unit: TIMING 2 is not 0 or 1"),
    ("schlick_narrowest",
     {"specular": {**SCHLICK, "schlick": {"quotient_bits": 1, "operand_bits": 2}}}, {}, None),
    ("schlick_quotient_0",
     {"specular": {**SCHLICK, "schlick": {"quotient_bits": 1, "operand_bits": 2}}},
     {"SPEC_PARAMS[0]": 0},
     r"schlick_divider: QUOTIENT_BITS 0 < 1" + or_zero_width("schlick_divider")),
    ("schlick_operand_1",
     {"specular": {**SCHLICK, "schlick": {"quotient_bits": 1, "operand_bits": 2}}},
     {"SPEC_PARAMS[1]": 1}, r"schlick_divider: OPERAND_BITS 1 < 2"),
    ("schlick_timing_2", {"specular": {**SCHLICK, "schlick": {"timing": "pipelined"}}},
     {"SPEC_PARAMS[2]": 2}, r"schlick_divider: TIMING 2 is not 0 or 1"),
]
SLOT = re.compile(r"SPEC_PARAMS\[(\d+)\]")


def run(cmd, cwd=None):
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)


def rtl_sources(source_dir):
    rtl = os.environ.get("SHADESIM_RTL_DIR") or os.path.join(source_dir, "rtl")
    with open(os.path.join(rtl, "files.f")) as f:
        files = [os.path.join(rtl, l.strip()) for l in f
                 if l.strip() and not l.strip().startswith("//")]
    return files


def parameters(shadesim, unit, work, name):
    path = os.path.join(work, name + ".json")
    with open(path, "w") as f:
        json.dump(unit, f)
    r = run([shadesim, "rtl-params", "--config", path, "--tool", "iverilog"])
    if r.returncode != 0:
        raise RuntimeError(f"{name}: shadesim rtl-params refused the unit: {r.stderr.strip()}")
    params = {}
    for line in r.stdout.split():
        m = re.fullmatch(r"-Ptb_shade_unit\.([A-Z0-9_]+)=(.*)", line)
        if m:
            params[m.group(1)] = m.group(2)
    return params


def with_slot(literal, slot, value):
    """SPEC_PARAMS's Verilog literal (W'hHEX, slot k at bits [32k +: 32]) with slot `slot` set."""
    width, digits = re.fullmatch(r"(\d+)'h([0-9a-fA-F]+)", literal).groups()
    bits = int(digits, 16) & ~(0xFFFFFFFF << (32 * slot)) | (value << (32 * slot))
    return f"{width}'h{bits:0{int(width) // 4}x}"


def check(case, args, sources):
    shadesim, iverilog, vvp, _, work = args
    name, unit, overrides, expected = case
    params = parameters(shadesim, unit, work, name)
    for key, value in overrides.items():
        slot = SLOT.fullmatch(key)
        if slot:
            params["SPEC_PARAMS"] = with_slot(params["SPEC_PARAMS"], int(slot.group(1)), value)
        else:
            params[key] = str(value)
    vvp_file = os.path.join(work, name + ".vvp")
    compiled = run([iverilog, "-g2012", "-s", "shade_unit", "-o", vvp_file] +
                   [f"-Pshade_unit.{k}={v}" for k, v in params.items()] + sources)
    if compiled.returncode != 0:
        if expected is not None and re.search(expected, compiled.stderr):
            return None  # refused while elaborating, by the expected module
        return f"does not compile: {compiled.stderr.strip().splitlines()[:3]}"
    ran = run([vvp, "-n", vvp_file])
    out = ran.stdout + ran.stderr
    fatal = "FATAL" in out or ran.returncode != 0
    if expected is None:
        return f"refused at a legal extreme: {out.strip()[-300:]}" if fatal else None
    if not fatal:
        return f"accepted, expected a $fatal matching '{expected}'"
    if not re.search(expected, out):
        return f"stopped, but not with '{expected}': {out.strip()[-300:]}"
    return None


def main():
    if len(sys.argv) != 6:
        sys.exit(__doc__)
    args = sys.argv[1:]
    os.makedirs(args[4], exist_ok=True)
    sources = rtl_sources(args[3])
    failed = 0
    with tempfile.TemporaryDirectory(dir=args[4]) as work:
        args[4] = work
        for case in CASES:
            problem = check(case, args, sources)
            edge = "legal" if case[3] is None else "past"
            print(f"{'FAIL' if problem else 'ok  '} {case[0]:<20} ({edge})"
                  + (f": {problem}" if problem else ""))
            failed += problem is not None
    print(f"param_extremes: {len(CASES) - failed} of {len(CASES)} cases behave")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
