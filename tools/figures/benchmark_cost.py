#!/usr/bin/env python3
"""The paper's §3.3 benchmark: wall time and peak memory of both models beside the paper's.

    tools/figures/draw benchmark_cost [--no-run] [--study DIR] [--out PNG]

Runs two one-point studies, one after the other (tools/study takes one tutorial per study):
tools/figures/benchmark_cost.toml, the benchmark tutorial as it is (direct model, 500
spheres, 648,000 cells, 0.1 s; one worker, `fsimFoam -threads 2`, so it has both cores and
nothing runs beside it), then tools/figures/benchmark_cost_draglaw.toml, benchmarkDragLaw
(drag-law model) the same way. Finished points are reused. Then it

- prints each run's wall time, CPU time and peak memory beside the paper's (§3.3: the direct
  model "about 82h of CPU time and 110 Mo of Memory", the drag law "less than 13mn and less
  0.5 Mo"), and the ratios paper / fsim;
- draws docs/figures/benchmark_cost.png: two bar panels, time (log axis) and peak memory,
  fsim's bars beside the paper's, each labelled with its value.

--study DIR names the benchmark's study folder; the drag law's is DIR with `-draglaw` added.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from figure import ROOT, arguments, run_study, study_tool  # noqa: E402

SPECS = (ROOT / "tools" / "figures" / "benchmark_cost.toml",
         ROOT / "tools" / "figures" / "benchmark_cost_draglaw.toml")
STUDY = ROOT / "studies" / "benchmark-cost"
OUT = ROOT / "docs" / "figures" / "benchmark_cost.png"
# The paper's §3.3: (model, CPU time in s, memory in MB). "Mo" is French for MB; the drag
# law's figures are upper bounds ("less than").
PAPER = (("direct", 82 * 3600.0, 110.0), ("drag law", 13 * 60.0, 0.5))


def drag_law_study(study):
    return study.with_name(study.name + "-draglaw")


def one_point(study):
    rows = study_tool.finished_points(study)
    if len(rows) != 1:
        raise SystemExit(f"{study}: {len(rows)} finished points, expected 1")
    return rows[0]


def duration(seconds):
    if seconds >= 3600:
        return f"{seconds / 3600:.3g} h"
    if seconds >= 60:
        return f"{seconds / 60:.3g} min"
    return f"{seconds:.3g} s"


def main(argv=None):
    args = arguments(__doc__, STUDY, OUT).parse_args(argv)
    studies = (args.study, drag_law_study(args.study))
    if not args.no_run:
        for spec, study in zip(SPECS, studies):
            run_study(spec, study)
    runs = [one_point(s) for s in studies]

    print("model     fsim: wall    CPU      threads  peak MB | paper: CPU  memory | "
          "paper/fsim: CPU/wall  CPU/CPU  memory")
    for (model, cpu, mem), r in zip(PAPER, runs):
        print(f"{model:<9} {duration(r['wall_time']):>10} {duration(r['cpu_time']):>8} "
              f"{r['threads']:>5.0f} {r['peak_memory_mb']:>9.1f} | {duration(cpu):>9} "
              f"{mem:>6g} MB | {cpu / r['wall_time']:>13.0f} {cpu / r['cpu_time']:>8.0f} "
              f"{mem / r['peak_memory_mb']:>7.3g}")
    direct, drag = runs
    print(f"\ndirect / drag law, fsim: wall {direct['wall_time'] / drag['wall_time']:.0f}, "
          f"memory {direct['peak_memory_mb'] / drag['peak_memory_mb']:.1f}; "
          f"paper: CPU {PAPER[0][1] / PAPER[1][1]:.0f}, memory {PAPER[0][2] / PAPER[1][2]:.0f}")

    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.8), constrained_layout=True)
    width = 0.36
    x = range(len(PAPER))
    bars = (("fsim (wall time, 2 threads)", "tab:blue", [r["wall_time"] for r in runs],
             [r["peak_memory_mb"] for r in runs]),
            ("paper §3.3 (CPU time)", "tab:gray", [p[1] for p in PAPER], [p[2] for p in PAPER]))
    for k, (label, colour, times, mems) in enumerate(bars):
        at = [i + (k - 0.5) * width for i in x]
        drawn = left.bar(at, times, width, color=colour, label=label)
        left.bar_label(drawn, [duration(t) for t in times], fontsize=8, padding=2)
        drawn = right.bar(at, mems, width, color=colour,
                          label=label.replace("wall time", "peak").replace("CPU time", "memory"))
        right.bar_label(drawn, [f"{m:.3g} MB" for m in mems], fontsize=8, padding=2)
    for ax in (left, right):
        ax.set_xticks(list(x), ["direct model\n(benchmark)", "drag-law model\n(benchmarkDragLaw)"])
        ax.legend(fontsize=8, loc="upper right")
    left.set_yscale("log")
    left.set_ylim(1, 3e6)
    left.set_ylabel("time (s, log scale)")
    left.set_title("time of 0.1 s simulated")
    right.set_ylim(0, 1.18 * max(max(r["peak_memory_mb"] for r in runs), PAPER[0][2]))
    right.set_ylabel("peak memory (MB)")
    right.set_title("peak memory")
    fig.suptitle("§3.3 benchmark, 500 spheres, 0.1 s: fsim against the paper (direct: 648,000 "
                 "cells, h = 0.4 r; drag law: 5,184 cells, h = 2 r)\n(the paper's drag-law "
                 "figures are upper bounds: \"less than 13 min and 0.5 MB\")", fontsize=10)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out, dpi=110)
    print(f"\nwrote {args.out.relative_to(ROOT) if args.out.is_relative_to(ROOT) else args.out}")


if __name__ == "__main__":
    main()
