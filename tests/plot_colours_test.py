#!/usr/bin/python3
"""scripts/plot gives every unit family (spec-error) and every stage (explore) its own colour,
and the explore plot names its start once and no cache key on an axis.

spec-error's plot colours must not repeat, however many families there are (a fixed palette
repeats silently once there are more families than it holds). This draws a spec-error report
with many families through scripts/plot's real plotting function and checks, on the figure
matplotlib built, that no two families' points share a colour; and checks distinct_colours
itself for every count up to 60.

  tests/plot_colours_test.py SOURCE_DIR
"""
import importlib.machinery
import importlib.util
import os
import sys
import tempfile


def load_plot(source_dir):
    path = os.path.join(source_dir, "scripts", "plot")
    loader = importlib.machinery.SourceFileLoader("shadesim_plot", path)
    spec = importlib.util.spec_from_loader("shadesim_plot", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


def rgb(c):
    return tuple(round(float(x), 4) for x in list(c)[:3])


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    plot = load_plot(sys.argv[1])
    failures = []
    for n in range(1, 61):
        colours = [rgb(c) for c in plot.distinct_colours(n)]
        if len(colours) != n or len(set(colours)) != n:
            failures.append(f"distinct_colours({n}) gives {len(set(colours))} distinct of {len(colours)}")

    # A spec-error report with 13 families (more than tab10 holds) and two units each.
    families = [f"fam{i:02d}" for i in range(13)]
    units = []
    for i, f in enumerate(families):
        for j in range(2):
            units.append({"name": f"{f} v{j}", "area": 100.0 * (i + 1) + j, "cycles_per_pixel": 1,
                          "abs_lsb": 1.0 / (i + 1 + j), "pareto": False})
    report = {"exponents": [16, 64], "units": units}
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "spec.png")
        plot.plot_spec_error(report, out)
        if not os.path.getsize(out) > 0:
            failures.append("plot_spec_error wrote an empty PNG")
    ax = plot.plt.gcf().axes[0]
    by_label = {}
    for coll in ax.collections:
        label = coll.get_label()
        if label in families:
            faces = {rgb(c) for c in coll.get_facecolors()}
            if len(faces) != 1:
                failures.append(f"family {label} drawn in {len(faces)} colours")
            by_label[label] = faces.pop()
    if sorted(by_label) != families:
        failures.append(f"families drawn: {sorted(by_label)}, expected {families}")
    if len(set(by_label.values())) != len(by_label):
        failures.append(f"{len(by_label)} families share {len(set(by_label.values()))} colours")
    plot.plt.close("all")

    failures += explore_legend_and_axes(plot)

    for f in failures:
        print("FAIL:", f)
    if failures:
        sys.exit(1)
    print(f"plot colours: distinct for 1..60 colours and for {len(families)} spec-error families")


def explore_legend_and_axes(plot):
    """An explore report whose start point is a stage of its own, with an area metric naming its
    Yosys anchor by cache key: the legend names the start once, the axis no cache key."""
    def point(stage, area, err, pareto=False):
        return {"valid": True, "stage": stage, "phase": "", "area": area, "cycles_per_pixel": 1.0,
                "pareto": pareto, "error": {"max_code_lsb": err, "mean_code_lsb": err / 4}}
    points = [point("start", 100.0, 1.0), point("coef", 90.0, 2.0, True), point("series", 80.0, 3.0)]
    key = "5f3a9c0e12d4b7a8"
    report = {"points": points, "start_index": 0, "chosen_index": 1, "start": {"out_bits": 8},
              "budget_lsb": 2, "scenes": ["scenes/sphere.json"],
              "area_metric": f"generic cells, estimate (scaled from Yosys run {key}, 2 parameters differ)"}
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        plot.plot_explore(report, os.path.join(tmp, "explore.png"))
    fig = plot.plt.gcf()
    labels = [t.get_text() for legend in fig.legends for t in legend.get_texts()]
    if labels.count("start") != 1:
        failures.append(f"explore legend names 'start' {labels.count('start')} times: {labels}")
    xlabels = " | ".join(ax.get_xlabel() for ax in fig.axes)
    if key in xlabels:
        failures.append(f"explore axis label carries the Yosys cache key: {xlabels}")
    plot.plt.close("all")
    return failures


if __name__ == "__main__":
    main()
