#!/usr/bin/python3
"""shadesim report, end to end, in headless Chromium.

  tests/report_page_test.py SHADESIM SOURCE_DIR WORK_DIR

Makes small inputs itself: render and cycles of scenes/sphere.json (on the unit
tests/data/report/sphere_unit.json), a short spec-error run, and hand-written explore, regress
and render --all-units JSON in their commands' formats (the first two need Yosys or the RTL,
minutes, which this test does not spend), a unit configuration and a JUnit file (both listed as
not read, with why). The silicon inputs are hand-written too (tests/data/report: area and layout
--json of that unit, with a stand-in layout PNG, and an area --json of another unit without a
scene; synthesis and layout take minutes): the Silicon section must put them beside the render's
error and the cycles, embed the PNG, judge the clock against the guard band, and say what is
missing. Writes the page, loads it in Debian's chromium
(--headless) and asserts that the screenshot is not blank (pixel spread and colours, decoded with
matplotlib), that the console logged no error, and that every section heading, the embedded
images, the failure's replay command, the cycles breakdown, the verdict line (FAIL: 1 of 2
regression runs failed) and the heat map's colour scale are in the DOM. First it checks
the console check itself on a page with a script error, so the check can fail. Then: a report
without inputs says so in every section and names the folder; a malformed input is named.
"""
import base64
import json
import os
import re
import shutil
import subprocess
import sys

SECTIONS = ["Inputs", "Scenes: model, reference, error", "Specular units: error against cost",
            "Width exploration", "Cycles per pixel", "Silicon: area, clock, energy, layout", "Regression",
            "Tool versions"]
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def run(args, **kw):
    r = subprocess.run(args, capture_output=True, text=True, timeout=600, **kw)
    return r


def chromium(url, work, tag):
    """(screenshot path, DOM text, console error lines) of a page loaded in headless chromium."""
    exe = shutil.which("chromium")
    if not exe:
        sys.exit("chromium is not installed: scripts/setup installs Debian's chromium")
    shot = os.path.join(work, tag + ".png")
    base = [exe, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--hide-scrollbars",
            "--user-data-dir=" + os.path.join(work, "chromium-profile-" + tag),
            "--enable-logging=stderr", "--v=0"]
    r1 = run(base + ["--window-size=1280,2000", "--screenshot=" + shot, url])
    r2 = run(base + ["--dump-dom", url])
    log = r1.stderr + r2.stderr
    console = [line for line in log.splitlines() if "CONSOLE" in line and
               re.search(r"error|Uncaught|Failed to load|ERR_", line, re.I)]
    return shot, r2.stdout, console


def not_blank(png):
    import matplotlib.image
    img = matplotlib.image.imread(png)[:, :, :3]
    colours = len({tuple(p) for p in (img[::4, ::4].reshape(-1, 3) * 255).astype(int).tolist()})
    return float(img.std()), colours


def row_cells(dom, first_cell):
    """The cells of the table row whose first cell is first_cell, or None."""
    m = re.search(r"<tr><td>" + re.escape(first_cell) + r"</td>(.*?)</tr>", dom)
    return re.findall(r"<td>(.*?)</td>", m.group(1)) if m else None


def kv(dom, start, heading):
    """The value of a key/value row after position start, or None."""
    m = re.compile(r"<tr><th>" + re.escape(heading) + r"</th><td>(.*?)</td></tr>").search(dom, start)
    return m.group(1) if m else None


def check_silicon(dom, sphere, data):
    """The Silicon section against the hand-written area and layout JSON (values typed in here)."""
    part = dom[dom.find('id="silicon'):]
    part = part[:part.find("</section>")]
    with open(os.path.join(sphere, "render.json")) as f:
        max_lsb = json.load(f)["error"]["max_code_lsb"]
    # Summary columns: unit, max LSB, cycles/px, GE, um^2, Fmax, clock, pJ/px, die, util, post Fmax,
    # DRC, LVS. Sphere's max LSB is the render's, matched to the area JSON by the unit's config.
    row = row_cells(part, "the unit of sphere")
    check(row is not None and row[0] == str(max_lsb) and row[1] != "-",
          f"sphere's unit row has the render's max error ({max_lsb} LSB) and the cycles/px: {row}")
    # Typed from tests/data/report/sphere_*.json; 351.2 MHz less 5 % is 333.6 >= 250, 0.555 is 55.5 %.
    check(row is not None and row[2:] == ["3090", "74861", "351.2", "met 250 MHz", "134.8", "0.1395",
                                          "55.5 %", "331.3", "0", "clean"],
          f"sphere's unit row: GE, um^2, Fmax, met, pJ/px, die, utilisation, post-route Fmax, DRC, LVS: {row}")
    sphere_at = part.find("<h3>the unit of sphere</h3>")
    check(sphere_at >= 0, "sphere's unit has its own details")
    for heading, want in [("clock uncertainty (ns)", "0.2"), ("guard band", "5 %"), ("inputs driven by", "BUFX2"),
                          ("wire length (um)", "101969"), ("vias", "11897"), ("core area (um^2)", "134912"),
                          ("LVS (netgen)", "clean (Circuits match uniquely.)"), ("DRC errors (magic)", "0"),
                          ("Fmax, same netlist without wires (MHz)", "351.2")]:
        got = kv(part, sphere_at, heading)
        check(got == want, f"sphere's unit: {heading} = {want} (got {got})")
    with open(os.path.join(data, "sphere_layout.png"), "rb") as f:
        png = base64.b64encode(f.read()).decode()
    check('src="data:image/png;base64,' + png + '"' in part, "the layout's PNG is embedded in the Silicon section")
    # The other unit: no scene, no layout; 256.4 MHz less 5 % is 243.6, under 250.
    row = row_cells(part, "unit specular_unit.json")
    check(row is not None and row[:2] == ["-", "-"] and row[5] == "missed 250 MHz" and row[6:] == ["-"] * 6,
          f"the other unit: no error, no cycles, misses the clock with the guard band, no layout: {row}")
    other = part[part.find("<h3>unit specular_unit.json</h3>"):sphere_at if sphere_at > 0 else None]
    check("no layout --json given" in other and "no render --json of this unit" in other and
          "energy: not in this area --json" in other, "the other unit says what is missing")
    check("243.6 MHz after the 5 % guard band" in other, "the other unit's clock verdict gives its margin")


def main():
    shadesim, src, work = sys.argv[1], sys.argv[2], os.path.abspath(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    inputs = os.path.join(work, "inputs")
    os.makedirs(os.path.join(inputs, "sphere"))

    # The console check must be able to fail: a page with a script error.
    bad = os.path.join(work, "bad.html")
    with open(bad, "w") as f:
        f.write("<!DOCTYPE html><html><body><h1>x</h1><script>no_such_function();</script></body></html>")
    _, _, console = chromium("file://" + bad, work, "bad")
    check(bool(console), "the console check sees a script error on a page that has one")

    sphere = os.path.join(inputs, "sphere")
    data = os.path.join(src, "tests", "data", "report")
    # The unit the hand-written area and layout JSON describe: render and cycles run on it.
    unit = os.path.join(data, "sphere_unit.json")
    r = run([shadesim, "render", os.path.join(src, "scenes/sphere.json"), "--config", unit, "--out", sphere,
             "--json", os.path.join(sphere, "render.json"), "-q"])
    check(r.returncode == 0, "render scenes/sphere.json --json: " + r.stderr.strip())
    r = run([shadesim, "cycles", os.path.join(src, "scenes/sphere.json"), "--config", unit,
             "--json", os.path.join(sphere, "cycles.json")])
    check(r.returncode == 0, "cycles scenes/sphere.json --json: " + r.stderr.strip())
    r = run([shadesim, "spec-error", "--exponents", "20,60,200", "--points", "16", "--no-papers",
             "--json", os.path.join(inputs, "spec-error.json")])
    check(r.returncode == 0, "spec-error --json: " + r.stderr.strip())
    # explore's format (sim/engines/explore.cpp), three points.
    def point(i, stage, area, mx, mean, pareto):
        return {"index": i, "phase": "stage", "stage": stage, "knob": stage, "value": str(i), "valid": True,
                "config_text": f"grey/1L point {i}", "error": {"max_code_lsb": mx, "mean_code_lsb": mean},
                "cycles_per_pixel": 2.687, "area": area, "pareto": pareto}
    explore = {"kind": "explore", "scenes": ["scenes/sphere.json"], "budget_lsb": 1, "area_metric": "cells (est.)",
               "start": {"out_bits": 8}, "start_index": 0, "chosen_index": 2,
               "points": [point(0, "coef", 16239, 1, 0.05, False), point(1, "series", 9000, 3, 0.6, True),
                          point(2, "series", 7525, 1, 0.09, True)]}
    with open(os.path.join(inputs, "explore.json"), "w") as f:
        json.dump(explore, f)
    # regress's format (sim/regress/regress.cpp write_json_report): one pass, one mismatch.
    replay = "build/shadesim cosim --stream out/regress/failing/torus.stream --seed 1"
    regress = {"passed": 1, "mismatched": 1, "errors": 0, "skipped": 0, "wall_seconds": 3.5, "seed": 1,
               "jobs": [{"scene": "scenes/sphere.json", "config": "own", "backend": "cpp", "status": "pass",
                         "pixels": 16176, "cycles": 43470, "cycles_per_pixel": 2.687, "seconds": 0.4,
                         "message": "", "replay": ""},
                        {"scene": "scenes/torus.json", "config": "grey_s428w", "backend": "systemc",
                         "status": "mismatch", "pixels": 19852, "cycles": 0, "cycles_per_pixel": 0,
                         "seconds": 0.9, "message": "pixel mismatch at (10, 20): expected 135, got 134",
                         "replay": replay}]}
    with open(os.path.join(inputs, "regress.json"), "w") as f:
        json.dump(regress, f)
    with open(os.path.join(inputs, "sphere", "unit.json"), "w") as f:
        json.dump({"channels": 1, "series": "s4.28"}, f)  # not a report: ignored, listed
    with open(os.path.join(inputs, "junit.xml"), "w") as f:
        f.write('<testsuite name="shadesim.regress"></testsuite>\n')  # read from regress --json instead
    # render --all-units's format (sim/engines/render.cpp run_all_units).
    with open(os.path.join(inputs, "units.json"), "w") as f:
        json.dump({"scene": "scenes/specular.json",
                   "units": [{"unit": "wpow", "configuration": "wpow m=16 B=16", "max_code_lsb": 2,
                              "mean_code_lsb": 0.22, "psnr_db": 52.8, "table_load_cycles": 0}]}, f)

    silicon = [os.path.join(data, f) for f in ("sphere_area.json", "sphere_layout.json",
                                               "specular_area_no_scene.json")]
    page_dir = os.path.join(work, "page")
    r = run([shadesim, "report", "--out", page_dir, inputs] + silicon)
    print(r.stdout)
    check(r.returncode == 0, f"report exits 0 on good inputs (got {r.returncode}; {r.stderr.strip()})")
    html_path = os.path.join(page_dir, "index.html")
    check(os.path.exists(html_path), "report writes index.html")
    with open(html_path) as f:
        html = f.read()
    check(not re.search(r"""(src|href)=["']?(https?:|//)""", html), "the page fetches nothing from the network")

    shot, dom, console = chromium("file://" + os.path.abspath(html_path), work, "report")
    check(not console, "no console errors loading the report: " + "; ".join(console))
    spread, colours = not_blank(shot)
    check(spread > 0.05 and colours > 50, f"screenshot not blank (pixel std {spread:.3f}, {colours} colours)")
    headings = re.findall(r"<h2>(.*?)</h2>", dom)
    for s in SECTIONS:
        check(s in headings, f"section '{s}' in the DOM")
    check(dom.count('src="data:image/png;base64,') >= 4,
          "render image, both plots and the layout picture are embedded in the DOM")
    # Headings in words, not JSON keys; no cycles per pixel for the run that stopped early.
    check(re.search(r"<th>\w+_\w+", dom) is None, "no table heading is a raw JSON key (snake_case)")
    failing_row = re.search(r"<tr>(?:<td>[^<]*</td>)*?<td>mismatch</td>.*?</tr>", dom)
    check(bool(failing_row) and "<td>0</td><td>0.9</td>" not in failing_row.group(0) and
          "<td>-</td>" in failing_row.group(0), "the failing run shows no cycles per pixel")
    # The verdict comes first, from the inputs' totals: one of the two regression runs failed.
    verdict = re.search(r'<p class="verdict (\w+)" id="verdict"><b>Verdict: (\w+)</b>: (.*?)</p>', dom)
    check(bool(verdict) and dom.find('id="verdict"') < dom.find("<h2>"), "a verdict line before the first section")
    if verdict:
        check(verdict.group(2) == "FAIL" and "1 of 2 regression runs failed" in verdict.group(3),
              "the verdict says FAIL, 1 of 2 regression runs failed: " + verdict.group(3))
    # The heat map's colour scale, at the full scale render used (--heat-scale, 4 LSB by default).
    with open(os.path.join(sphere, "render.json")) as f:
        full = json.load(f)["heat_scale_lsb"]
    check(full == 4, f"render.json records the heat map's full scale (4 LSB by default, got {full})")
    check(re.search(r'class="scale">error colour scale:.*0 LSB.*class="bar".*\b4 LSB and more', dom) is not None,
          "the error heat map has its colour scale, 0 to 4 LSB")
    check(replay in dom, "the failure's replay command is on the page")
    check("grey_s428w" in dom and "mismatch" in dom, "the regression table lists the failing run")
    with open(os.path.join(sphere, "cycles.json")) as f:
        rows = json.load(f)["breakdown"]
    missing = [r["name"] for r in rows if f"<td>{r['name']}</td><td>{r['cycles']}</td>" not in dom]
    check(rows and not missing, f"every cycles breakdown row with its cycles is on the page (missing: {missing})")
    check("No input" not in dom, "every section has its input")
    check("unit.json" in dom and "a unit configuration, not a report" in dom, "a non-report file is listed as ignored")
    check("junit.xml" in dom and "JUnit XML is not read" in dom, "a JUnit file is listed with where its runs are read")
    check("specular: every specular unit" in dom and "wpow m=16 B=16" in dom, "render --all-units's table is on the page")

    check_silicon(dom, sphere, data)

    # Nothing to read: every section says so, and the folder is named.
    empty = os.path.join(work, "empty")
    os.makedirs(empty)
    r = run([shadesim, "report", "--out", os.path.join(work, "page-empty"), empty])
    check(r.returncode == 1 and empty in r.stdout and "holds no report" in r.stdout,
          "an empty folder: exit 1, the folder named (" + r.stdout.strip().replace("\n", " | ") + ")")
    with open(os.path.join(work, "page-empty", "index.html")) as f:
        empty_html = f.read()
    check(empty_html.count("No input") == 6, f"each of the 6 report sections says it has no input "
          f"({empty_html.count('No input')})")

    # A malformed input is named, with what was expected.
    broken = os.path.join(work, "broken.json")
    with open(broken, "w") as f:
        f.write('{"jobs": [')
    r = run([shadesim, "report", "--out", os.path.join(work, "page-broken"), broken])
    check(r.returncode == 1 and broken + ": not valid JSON" in r.stdout and "expected the JSON of" in r.stdout,
          "a malformed file: exit 1, named, with what was expected")

    # A layout --json with a figure of the wrong type and one missing: named, with what was
    # expected, exit 1, and the page still written.
    malformed = os.path.join(data, "layout_malformed.json")
    page_bad = os.path.join(work, "page-malformed")
    r = run([shadesim, "report", "--out", page_bad, malformed])
    check(r.returncode == 1 and malformed + ": has the keys of layout --json" in r.stdout and
          "timing.fmax_mhz is string, expected a number" in r.stdout and
          "lvs.clean is missing, expected true or false" in r.stdout,
          "a malformed layout --json: exit 1, named, the fields and what was expected (" +
          r.stdout.strip().replace("\n", " | ") + ")")
    bad_html = os.path.join(page_bad, "index.html")
    with open(bad_html) if os.path.exists(bad_html) else open(os.devnull) as f:
        bad_dom = f.read()
    inputs_part = bad_dom[bad_dom.find('id="inputs"'):bad_dom.find('id="scenes')]
    check("layout_malformed.json" in inputs_part and "timing.fmax_mhz is string" in inputs_part,
          "the malformed layout --json is listed under Inputs on the page written anyway")

    print(f"\nreport_page_test: {len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
