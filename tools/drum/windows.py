#!/usr/bin/python3
"""Drum runs side by side over windows of simulated time: is the bed carried by the drum?

Each RUN is LABEL=CACHE, a drum_metrics metrics cache (one row per snapshot, e.g. a study's
docs/drum/NAME/<rpm>rpm/partial/metrics_cache.csv). For each run and each window of --window
seconds from the first snapshot, the mean of each metric over the window's snapshots; a window
holds a few slumps and a fraction of a revolution, so the means show trends, not steady averages
(use `drum_metrics steady` for those). Writes OUT.md (a table per metric) and OUT.png (the
series, window means as steps).

  tools/drum/windows.py --rpm 21 --out docs/drum/walls_21rpm \\
      cylinder=docs/drum/history_21rpm_settled/21rpm/partial/metrics_cache.csv \\
      moving=docs/drum/walls_21rpm_moving/21rpm/partial/metrics_cache.csv

Needs: python3-matplotlib (tools/harness); drum_metrics.
"""

import argparse
import math
import shlex
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import harness  # noqa: E402
from harness import charts  # noqa: E402

SHOWN = ["bed_turn", "wall_roll", "wall_slip", "Hc", "angle", "surface_velocity"]


def windows(rows, width):
    """[(start, end, rows)]: the rows in consecutive half-open windows [t0 + k width, t0 + (k + 1)
    width) from the first row's time t0 (times a rounding error short of a boundary count as on
    it); a window whose rows span less than half the width (a short tail) is dropped."""
    t0 = rows[0]["time_s"]
    groups = {}
    for r in rows:
        groups.setdefault(math.floor((r["time_s"] - t0) / width + 1e-9), []).append(r)
    return [(t0 + k * width, t0 + k * width + width, g) for k, g in sorted(groups.items())
            if g[-1]["time_s"] - (t0 + k * width) >= width / 2 - 1e-9]


def mean(rows, column):
    v = [r[column] for r in rows if isinstance(r[column], float) and math.isfinite(r[column])]
    return sum(v) / len(v) if v else float("nan")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    p.add_argument("runs", nargs="+", metavar="LABEL=CACHE")
    p.add_argument("--rpm", type=float, required=True, help="drum speed (titles)")
    p.add_argument("--window", type=float, default=2.0, help="window length [s] (default: 2)")
    p.add_argument("--out", type=Path, required=True, help="OUT.md and OUT.png")
    args = p.parse_args()
    table = {m["key"]: m for m in harness.drum_metric_table()}
    runs = []
    for spec in args.runs:
        label, sep, path = spec.partition("=")
        if not sep or not label:
            raise SystemExit(f"windows: '{spec}' is not LABEL=CACHE")
        rows = harness.read_csv(path)
        if len(rows) < 2:
            raise SystemExit(f"windows: {path} holds {len(rows)} snapshot(s); windows need at least 2")
        missing = [k for k in SHOWN if table[k]["column"] not in rows[0]]
        if missing:
            raise SystemExit(f"windows: {path} has no column for {', '.join(missing)}: "
                             f"measure it with this drum_metrics (`drum_metrics series --cache` upgrades it)")
        runs.append((label, path, rows))

    command = "tools/drum/windows.py " + shlex.join(sys.argv[1:])
    md = [harness.generated_note(command),
          f"# {args.rpm:g} rpm: runs over {args.window:g} s windows\n",
          "Means over each window of the snapshots' metrics (`drum_metrics metrics` defines them). "
          "Sources: " + ", ".join(f"{label}: `{path}`" for label, path, _ in runs) + ".\n"]
    fig, axes = charts.figure(2, 3, f"{args.rpm:g} rpm: window means (steps) over the snapshots")
    for ax, key in zip(axes, SHOWN):
        m = table[key]
        rows = []
        for label, _, series in runs:
            ws = windows(series, args.window)
            rows += [{"run": label, "from": a, "to": b, "snapshots": len(w), "mean": mean(w, m["column"])}
                     for a, b, w in ws]
            line, = ax.plot([r["time_s"] for r in series], [r[m["column"]] for r in series], lw=0.6, alpha=0.5,
                            label=label)
            for a, b, w in ws:
                ax.hlines(mean(w, m["column"]), a, b, colors=line.get_color(), lw=2.5)
        ax.set_xlabel("time [s]")
        ax.set_ylabel(f"{m['label']} [{m['unit']}]")
        ax.legend(fontsize=8)
        md.append(f"\n## {m['label']} [{m['unit']}]\n\n{m['description']}.\n\n")
        md.append(harness.markdown(rows, [("run", "run", None), ("from [s]", "from", "{:.2f}"),
                                          ("to [s]", "to", "{:.2f}"), ("snapshots", "snapshots", None),
                                          ("mean", "mean", "{:.4g}")]))
    charts.save(fig, args.out.with_suffix(".png"))
    args.out.with_suffix(".md").write_text("".join(md))
    print(f"windows: {args.out.with_suffix('.md')}, {args.out.with_suffix('.png')}")


if __name__ == "__main__":
    main()
