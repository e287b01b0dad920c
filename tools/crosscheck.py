#!/usr/bin/env python3
"""Runs one case under OpenFOAM's DPMFoam and under fsimFoam and compares what both computed.

    tools/crosscheck CASE [--set FILE:ENTRY=VALUE ...] [--threads N] [--keep DIR]
                          [--reference | --write-reference] [--fsim PATH] [--out DIR]

CASE is an OpenFOAM case directory with a `crosscheck.toml` that names the quantities, their
tolerances and the reasons for them (docs/crosscheck.md). Both programs run in scratch copies
of the case: DPMFoam after blockMesh, fsimFoam as it is. The quantities are computed from the
time directories both write (DPMFoam's ascii `lagrangian/` cloud fields and fields, fsim's
`particles.vtu` and `fluid.vtk`), and printed as a table: quantity, DPMFoam, fsim, difference,
tolerance, pass, with both wall times, their ratio and both peak memories. The table goes to
`crosscheck.csv` and both histories to `crosscheck.png` (in --out, default the case folder).

Exit status: 0 when every quantity is within its tolerance; 1 when one is not (each named);
2 when a program fails or the case or its crosscheck.toml is wrong.

Without DPMFoam (no OpenFOAM installed), or with --reference, DPMFoam's histories come from
`crosscheck_reference.csv` in the case, written by --write-reference from a real DPMFoam run
with its version and date; the table says so.
"""
import argparse
import csv
import datetime
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import foam_dict  # noqa: E402
from measured_run import wait_measured  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
FOAM_ENV = {"WM_PROJECT_DIR": "/usr/share/openfoam", "FOAM_ETC": "/usr/share/openfoam/etc"}
CASE_FILES = ("system", "constant", "0")
REFERENCE = "crosscheck_reference.csv"
STATISTICS = ("final", "mean", "min", "max", "history", "restitution")


class CaseError(Exception):
    """A case, its crosscheck.toml or a run that cannot be compared (exit 2)."""


# ----- the specification ------------------------------------------------------------------

def load_spec(case):
    path = case / "crosscheck.toml"
    try:
        spec = tomllib.loads(path.read_text())
    except FileNotFoundError:
        raise CaseError(f"{path}: no such file (the quantities to compare)")
    except tomllib.TOMLDecodeError as e:
        raise CaseError(f"{path}: {e}")
    quantities = spec.get("quantity", [])
    if not quantities:
        raise CaseError(f"{path}: no [[quantity]]")
    for q in quantities:
        for key in ("name", "series", "statistic", "tolerance"):
            if key not in q:
                raise CaseError(f"{path}: quantity {q.get('name', '?')!r} has no '{key}'")
        if q["statistic"] not in STATISTICS:
            raise CaseError(f"{path}: quantity {q['name']!r}: statistic {q['statistic']!r} "
                            f"is not one of {', '.join(STATISTICS)}")
        parse_series(q["series"], path)
    return spec


def parse_series(name, where="--"):
    """`particles.U.z.mean` -> ('particles', 'U', 'z', 'mean'); `fluid.dp.a.b`; checked."""
    parts = name.split(".")
    ok = (parts[0] == "particles" and (parts[1:] == ["count"] or (
        len(parts) == 4 and parts[1] in ("U", "position", "omega")
        and parts[2] in ("x", "y", "z", "mag")
        and re.fullmatch(r"mean|min|max|id:\d+|rel:\d+:\d+", parts[3])))) or (
        parts[0] == "fluid" and ((parts[1] == "p" and len(parts) == 3)
                                 or (parts[1] == "dp" and len(parts) == 4)))
    if not ok:
        raise CaseError(f"{where}: series {name!r} is not one of particles.<U|position|omega>."
                        "<x|y|z|mag>.<mean|min|max|id:N|rel:A:B>, particles.count, "
                        "fluid.p.<patch>, fluid.dp.<patchA>.<patchB>")
    return parts


# ----- scratch copies and runs ----------------------------------------------------------

def scratch_copy(case, dest, sets):
    """The case's system/, constant/ and 0/ (and other regular files, not outputs) in
    `dest`, with the --set changes applied."""
    dest.mkdir(parents=True)
    for name in CASE_FILES:
        if (case / name).is_dir():
            shutil.copytree(case / name, dest / name, symlinks=False,
                            ignore=shutil.ignore_patterns("*.vtk", "*.vti", "*.vtu", "*.bin"))
    for entry in sets:
        apply_set(dest, entry)


def apply_set(case, entry):
    """`FILE:ENTRY=VALUE`, as foamDictionary -entry ENTRY -set VALUE on case/FILE."""
    m = re.fullmatch(r"([^:]+):([^=]+)=(.*)", entry)
    if not m:
        raise CaseError(f"--set {entry!r}: expected FILE:ENTRY=VALUE")
    path = case / m.group(1)
    try:
        text = foam_dict.set_entry(path.read_text(), m.group(2), m.group(3))
    except KeyError as e:
        raise CaseError(f"--set {entry!r}: {m.group(1)} has no entry {e.args[0]!r}")
    except (OSError, ValueError) as e:
        raise CaseError(f"--set {entry!r}: {e}")
    path.write_text(text)


def run(cmd, cwd, log, env=None):
    """Runs `cmd` in `cwd` with its output in `log`; (wall s, peak resident MB) or CaseError."""
    start = time.perf_counter()
    with open(log, "w") as out:
        proc = subprocess.Popen(cmd, cwd=cwd, stdout=out, stderr=subprocess.STDOUT,
                                env={**os.environ, "PWD": str(cwd), **(env or {})})
        code, _, peak = wait_measured(proc)
    wall = time.perf_counter() - start
    if code != 0:
        tail = "".join(Path(log).read_text(errors="replace").splitlines(True)[-15:])
        raise CaseError(f"{' '.join(map(str, cmd))} failed with exit {code} in {cwd}:\n{tail}")
    return wall, peak / 2**20


def fsim_binary(given):
    if given:
        return Path(given).resolve()
    if os.environ.get("FSIM"):
        return Path(os.environ["FSIM"]).resolve()
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    target = target if target.is_absolute() else ROOT / target
    binary = target / "release" / "fsimFoam"
    subprocess.run(["cargo", "build", "--release", "--quiet", "--bin", "fsimFoam"], cwd=ROOT,
                   check=True)
    return binary


def dpmfoam_available():
    return shutil.which("DPMFoam") is not None and shutil.which("blockMesh") is not None


# ----- reading what the programs wrote ------------------------------------------------------

def time_dirs(case):
    """(time, path) of the numeric time directories, ascending."""
    found = []
    for p in case.iterdir():
        if p.is_dir() and re.fullmatch(r"[-+]?[0-9.]+(e[-+]?\d+)?", p.name):
            found.append((float(p.name), p))
    return sorted(found)


class Mesh:
    """The blockMesh mesh's cells next to each patch (from polyMesh's boundary and owner),
    which index fsim's cells as well: one uniform block, cells x fastest in both."""

    def __init__(self, case):
        poly = case / "constant" / "polyMesh"
        owner_text = (poly / "owner").read_text()
        m = re.search(r"nCells:\s*(\d+)", owner_text)
        self.cells = int(m.group(1))
        owner = foam_dict.read_list(owner_text, 1).astype(int)
        boundary = foam_dict.body((poly / "boundary").read_text())
        self.patches = {}
        for name, body in re.findall(r"^\s*(\w+)\s*\{([^}]*)\}", boundary, re.M):
            start = int(re.search(r"startFace\s+(\d+)", body).group(1))
            count = int(re.search(r"nFaces\s+(\d+)", body).group(1))
            self.patches[name] = np.unique(owner[start:start + count])

    @classmethod
    def from_reference(cls, meta):
        """The cells next to each patch as the reference file recorded them."""
        mesh = cls.__new__(cls)
        mesh.cells = int(meta.get("cells", 0))
        mesh.patches = {key[len("cells next to "):]: np.array(value.split(), dtype=int)
                        for key, value in meta.items() if key.startswith("cells next to ")}
        return mesh

    def reference_meta(self, spec):
        """The cell count and the cells next to the patches the quantities name."""
        meta = {"cells": str(self.cells)}
        for q in spec["quantity"]:
            parts = q["series"].split(".")
            for name in parts[2:] if parts[0] == "fluid" else []:
                meta[f"cells next to {name}"] = " ".join(map(str, self.next_to(name)))
        return meta

    def next_to(self, patch):
        if patch not in self.patches:
            raise CaseError(f"no patch {patch!r} (patches: {', '.join(self.patches)})")
        return self.patches[patch]


def fluid_density(case):
    text = (case / "constant" / "transportProperties").read_text()
    phase = re.search(r"^\s*continuousPhase\s+(\w+)\s*;", text, re.M)
    key = f"rho.{phase.group(1)}" if phase else "rho"
    m = re.search(rf"^\s*{re.escape(key)}\s+(?:\[[^\]]*\]\s*)?([-+0-9.eE]+)\s*;", text, re.M)
    return float(m.group(1)) if m else 1.0


class Snapshot:
    """One written time of one program: the particles (id, position, U, omega, d) sorted by
    id, and the kinematic pressure per cell (None when not read: no quantity needs it)."""

    def __init__(self, ids, position, velocity, omega, p):
        order = np.argsort(ids)
        self.ids = ids[order]
        self.position, self.U, self.omega = position[order], velocity[order], omega[order]
        self.p = p


def dpmfoam_snapshot(path, cells, fluid):
    cloud = path / "lagrangian" / "kinematicCloud"
    if (cloud / "positions").is_file():
        read = lambda name, w: foam_dict.read_list((cloud / name).read_text(), w)  # noqa: E731
        position = read("positions", 3)
        velocity, d = read("U", 3), read("d", 1)
        ids = read("origId", 1).astype(int)
        if (cloud / "angularMomentum").is_file():
            rho = read("rho", 1)
            inertia = rho * math.pi * d ** 5 / 60  # m d^2 / 10 of a sphere
            omega = read("angularMomentum", 3) / inertia[:, None]
        else:
            omega = np.zeros_like(velocity)
    else:
        position = velocity = omega = np.zeros((0, 3))
        ids = np.zeros(0, dtype=int)
    p = None
    if fluid and (path / "p").is_file():
        p = foam_dict.read_internal_field((path / "p").read_text(), cells)
    return Snapshot(ids, position, velocity, omega, p)


def fsim_snapshot(path, fluid):
    import meshio
    if (path / "particles.vtu").is_file():
        m = meshio.read(path / "particles.vtu")
        data = m.point_data
        snap = (np.asarray(data["id"]).astype(int).ravel(), np.asarray(m.points),
                np.asarray(data["U"]), np.asarray(data["omega"]))
    else:
        snap = (np.zeros(0, dtype=int), np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3)))
    p = None
    if fluid and (path / "fluid.vtk").is_file():
        p = np.asarray(meshio.read(path / "fluid.vtk").cell_data["p"][0]).ravel()
    return Snapshot(*snap, p)


def component(values, comp):
    if comp == "mag":
        return np.linalg.norm(values, axis=1)
    return values[:, "xyz".index(comp)]


def series_value(parts, snap, mesh, rho):
    """The value of a parsed series at one snapshot (NaN where it has no value)."""
    if parts[0] == "particles":
        if parts[1] == "count":
            return float(len(snap.ids))
        field = {"U": snap.U, "position": snap.position, "omega": snap.omega}[parts[1]]
        if len(snap.ids) == 0:
            return math.nan
        values = component(field, parts[2])
        how = parts[3]
        if how in ("mean", "min", "max"):
            return float(getattr(np, how)(values))
        ids = [int(k) for k in how.split(":")[1:]]
        found = [np.searchsorted(snap.ids, k) for k in ids]
        if any(i >= len(snap.ids) or snap.ids[i] != k for i, k in zip(found, ids)):
            return math.nan
        return float(values[found[0]]) if how.startswith("id:") else \
            float(values[found[1]] - values[found[0]])
    if snap.p is None:
        return math.nan
    if len(snap.p) != mesh.cells:
        raise CaseError(f"the fluid has {len(snap.p)} cells, blockMesh's mesh {mesh.cells}")
    mean = lambda patch: float(snap.p[mesh.next_to(patch)].mean()) * rho  # noqa: E731
    return mean(parts[2]) if parts[1] == "p" else mean(parts[2]) - mean(parts[3])


def histories(snapshots, spec, mesh, rho, shift=0.0):
    """{series name: (times, values)} of every series the spec names."""
    names = sorted({q["series"] for q in spec["quantity"]})
    out = {}
    for name in names:
        parts = parse_series(name)
        times, values = [], []
        for t, snap in snapshots:
            times.append(t + shift)
            values.append(series_value(parts, snap, mesh, rho))
        out[name] = (np.array(times), np.array(values))
    return out


# ----- the comparison ------------------------------------------------------------------------

def windowed(history, window):
    """The samples in the window, and the history's value at each end of the window that falls
    between two of its samples (linear): both programs' statistics then cover the same
    interval even where `dpmfoam_shift_steps` moves DPMFoam's samples off the window's ends
    (docs/crosscheck.md)."""
    t, v = history
    keep = ~np.isnan(v)
    t, v = t[keep], v[keep]
    if not window or len(t) == 0:
        return t, v
    eps = 1e-12
    inside = (t >= window[0] - eps) & (t <= window[1] + eps)
    ends = [e for e in window
            if t[0] < e - eps and e + eps < t[-1] and not np.any(np.abs(t - e) <= eps)]
    tw = np.concatenate([t[inside], ends])
    vw = np.concatenate([v[inside], np.interp(ends, t, v)])
    order = np.argsort(tw, kind="stable")
    return tw[order], vw[order]


def statistic(q, history):
    """The quantity of one program from its history (NaN when the window is empty)."""
    t, v = windowed(history, q.get("window"))
    if len(t) == 0:
        return math.nan
    kind = q["statistic"]
    if kind == "final":
        return float(v[-1])
    if kind == "mean":
        return float(np.trapezoid(v, t) / (t[-1] - t[0])) if len(t) > 1 else float(v[0])
    if kind in ("min", "max"):
        return float(getattr(np, kind)(v))
    if kind == "restitution":
        return float(-v[-1] / v[0])
    raise AssertionError(kind)


def history_difference(q, dpm, fsim):
    """max |fsim - dpm| / max |dpm| over the window, fsim interpolated to DPMFoam's times."""
    td, vd = windowed(dpm, q.get("window"))
    tf, vf = windowed(fsim, q.get("window"))
    if len(td) == 0 or len(tf) == 0:
        return math.nan
    inside = (td >= tf[0] - 1e-12) & (td <= tf[-1] + 1e-12)
    diff = np.abs(np.interp(td[inside], tf, vf) - vd[inside])
    return float(diff.max() / np.abs(vd).max())


def compare(spec, dpm_hist, fsim_hist):
    """One row per quantity: name, DPMFoam, fsim, difference, tolerance, pass."""
    rows = []
    for q in spec["quantity"]:
        relative = q.get("relative", True)
        if q["statistic"] == "history":
            d = f = math.nan
            diff = history_difference(q, dpm_hist[q["series"]], fsim_hist[q["series"]])
            relative = True
        else:
            d = statistic(q, dpm_hist[q["series"]])
            f = statistic(q, fsim_hist[q["series"]])
            diff = abs(f - d) / abs(d) if relative and d != 0 else abs(f - d)
        ok = bool(diff <= q["tolerance"])  # NaN fails
        rows.append({"quantity": q["name"], "statistic": q["statistic"],
                     "unit": q.get("unit", ""), "dpmfoam": d, "fsim": f,
                     "difference": diff, "tolerance": q["tolerance"],
                     "relative": relative, "pass": ok})
    return rows


# ----- the reference file (DPMFoam's histories without DPMFoam) -------------------------------

def write_reference(path, hist, meta):
    names = sorted(hist)
    times = hist[names[0]][0]
    with open(path, "w", newline="") as f:
        for key, value in meta.items():
            f.write(f"# {key}: {value}\n")
        w = csv.writer(f)
        w.writerow(["time"] + names)
        for k, t in enumerate(times):
            w.writerow([repr(float(t))] + [repr(float(hist[n][1][k])) for n in names])


def read_reference(path, spec):
    meta, lines = {}, []
    for line in path.read_text().splitlines():
        if line.startswith("#"):
            key, _, value = line[1:].partition(":")
            meta[key.strip()] = value.strip()
        else:
            lines.append(line)
    rows = list(csv.reader(lines))
    header, data = rows[0], np.array([[float(x) for x in r] for r in rows[1:]])
    hist = {}
    for q in spec["quantity"]:
        if q["series"] not in header:
            raise CaseError(f"{path}: no column {q['series']!r}; rerun --write-reference")
        hist[q["series"]] = (data[:, 0], data[:, header.index(q["series"])])
    return hist, meta


# ----- output ---------------------------------------------------------------------------------

def fmt(x):
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.5g}"


def print_table(rows, info):
    head = ["quantity", "DPMFoam", "fsim", "difference", "tolerance", "pass"]
    body = []
    for r in rows:
        unit = f" ({r['unit']})" if r["unit"] else ""
        kind = "rel" if r["relative"] else "abs"
        diff = f"{100 * r['difference']:.3g} %" if r["relative"] else fmt(r["difference"])
        tol = f"{100 * r['tolerance']:.3g} %" if r["relative"] else fmt(r["tolerance"])
        body.append([f"{r['quantity']} [{r['statistic']}]{unit}", fmt(r["dpmfoam"]),
                     fmt(r["fsim"]), diff, f"{tol} {kind}", "yes" if r["pass"] else "NO"])
    widths = [max(len(x[i]) for x in [head] + body) for i in range(len(head))]
    line = lambda cells: "  ".join(c.ljust(w) for c, w in zip(cells, widths))  # noqa: E731
    print(line(head))
    print(line(["-" * w for w in widths]))
    for b in body:
        print(line(b))
    print(info)


def write_csv(path, rows, meta):
    with open(path, "w", newline="") as f:
        for key, value in meta.items():
            f.write(f"# {key}: {value}\n")
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def draw(path, spec, dpm_hist, fsim_hist, title, dpm_label):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    names = []
    for q in spec["quantity"]:
        if q["series"] not in names:
            names.append(q["series"])
    fig, axes = plt.subplots(len(names), 1, figsize=(7.5, 2.6 * len(names)), squeeze=False,
                             constrained_layout=True)
    for ax, name in zip(axes[:, 0], names):
        td, vd = dpm_hist[name]
        tf, vf = fsim_hist[name]
        ax.plot(td, vd, "o-", ms=3, lw=1.2, color="tab:blue", label=dpm_label)
        ax.plot(tf, vf, "s--", ms=2.5, lw=1.2, color="tab:orange", label="fsimFoam")
        for q in spec["quantity"]:
            if q["series"] == name and q.get("window"):
                ax.axvspan(*q["window"], color="0.9", zorder=0)
        named = [q for q in spec["quantity"] if q["series"] == name]
        unit = named[0].get("unit", "")
        ax.set_title(", ".join(q["name"] for q in named) + f" ({name})", fontsize=9)
        ax.set_ylabel(unit, fontsize=9)
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    axes[-1, 0].set_xlabel("t (s)")
    fig.suptitle(title, fontsize=10)
    fig.savefig(path, dpi=100)
    plt.close(fig)


# ----- the command ------------------------------------------------------------------------------

def openfoam_version(log_text):
    m = re.search(r"^Build\s*:\s*OPENFOAM=(\d+)(?:\s+patch=(\d+))?", log_text, re.M)
    if not m:
        return "unknown"
    return f"v{m.group(1)}" + (f" (patch {m.group(2)})" if m.group(2) else "")


def crosscheck(args):
    case = Path(args.case).resolve()
    if not (case / "system" / "controlDict").is_file():
        raise CaseError(f"{case}: not a case (no system/controlDict)")
    spec = load_spec(case)
    out = Path(args.out).resolve() if args.out else case
    scratch = Path(args.keep).resolve() if args.keep else Path(tempfile.mkdtemp(prefix="crosscheck."))
    if args.keep and scratch.exists():
        shutil.rmtree(scratch)
    use_reference = args.reference or not dpmfoam_available()
    try:
        dpm_dir, fsim_dir = scratch / "dpmfoam", scratch / "fsim"
        scratch_copy(case, dpm_dir, args.set)
        scratch_copy(case, fsim_dir, args.set)
        rho = fluid_density(dpm_dir)
        fluid = any(q["series"].startswith("fluid.") for q in spec["quantity"])  # read p?
        control = (dpm_dir / "system" / "controlDict").read_text()
        delta_t = float(foam_dict.get_entry(control, "deltaT"))
        shift = spec.get("dpmfoam_shift_steps", 0) * delta_t
        meta = {}
        if use_reference:
            ref = case / REFERENCE
            if not ref.is_file():
                raise CaseError(f"no DPMFoam here and no {ref} to compare with")
            dpm_hist, meta = read_reference(ref, spec)
            mesh = Mesh.from_reference(meta)
            dpm_wall = float(meta.get("DPMFoam wall time (s)", "nan"))
            dpm_mem = float(meta.get("DPMFoam peak memory (MB)", "nan"))
            source = (f"DPMFoam {meta.get('DPMFoam version', '?')} from {REFERENCE} "
                      f"(run {meta.get('date', '?')}), not run here")
        else:
            run(["blockMesh"], dpm_dir, dpm_dir / "log.blockMesh", FOAM_ENV)
            mesh = Mesh(dpm_dir)
            dpm_wall, dpm_mem = run(["DPMFoam"], dpm_dir, dpm_dir / "log.DPMFoam", FOAM_ENV)
            version = openfoam_version((dpm_dir / "log.DPMFoam").read_text())
            snaps = [(t, dpmfoam_snapshot(p, mesh.cells, fluid)) for t, p in time_dirs(dpm_dir)
                     if t > 0 or (p / "lagrangian").is_dir()]
            dpm_hist = histories(snaps, spec, mesh, rho, shift)
            source = f"DPMFoam {version}, run here"
            meta = {"DPMFoam version": version,
                    "date": datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC"),
                    "DPMFoam wall time (s)": f"{dpm_wall:.2f}",
                    "DPMFoam peak memory (MB)": f"{dpm_mem:.1f}",
                    "changes": " ".join(args.set) or "none"}
            if args.write_reference:
                meta.update(mesh.reference_meta(spec))
                write_reference(case / REFERENCE, dpm_hist, meta)
        fsim = fsim_binary(args.fsim)
        cmd = [str(fsim), "-case", str(fsim_dir)] + (
            ["-threads", str(args.threads)] if args.threads else [])
        fsim_wall, fsim_mem = run(cmd, fsim_dir, fsim_dir / "log.fsimFoam")
        snaps = [(t, fsim_snapshot(p, fluid)) for t, p in time_dirs(fsim_dir)]
        fsim_hist = histories(snaps, spec, mesh, rho)
    finally:
        if not args.keep:
            shutil.rmtree(scratch, ignore_errors=True)

    rows = compare(spec, dpm_hist, fsim_hist)
    threads = args.threads or "default"
    info = (f"{source}: {fmt(dpm_wall)} s wall, {fmt(dpm_mem)} MB peak (serial)\n"
            f"fsimFoam ({threads} threads): {fsim_wall:.2f} s wall, {fsim_mem:.1f} MB peak; "
            f"DPMFoam / fsim wall time: {fmt(dpm_wall / fsim_wall)}")
    print(f"== crosscheck {case.name}: {spec.get('description', '')}")
    print_table(rows, info)
    out.mkdir(parents=True, exist_ok=True)
    write_csv(out / "crosscheck.csv", rows, {
        "case": case.name, "source": source, "DPMFoam wall (s)": fmt(dpm_wall),
        "fsim wall (s)": f"{fsim_wall:.3f}", "fsim threads": threads,
        "DPMFoam peak (MB)": fmt(dpm_mem), "fsim peak (MB)": f"{fsim_mem:.1f}"})
    draw(out / "crosscheck.png", spec, dpm_hist, fsim_hist, f"{case.name}\n{source}",
         "DPMFoam (reference file)" if use_reference else "DPMFoam")
    failed = [r["quantity"] for r in rows if not r["pass"]]
    for name in failed:
        print(f"FAILED: {name}", file=sys.stderr)
    return 1 if failed else 0


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("case")
    parser.add_argument("--set", action="append", default=[], metavar="FILE:ENTRY=VALUE",
                        help="change an entry in both copies (foamDictionary -entry -set)")
    parser.add_argument("--threads", type=int, default=1,
                        help="fsimFoam's threads (default 1: serial against serial DPMFoam)")
    parser.add_argument("--keep", metavar="DIR", help="run in DIR and keep it")
    parser.add_argument("--out", metavar="DIR", help="where crosscheck.csv/png go (the case)")
    parser.add_argument("--fsim", metavar="PATH", help="the fsimFoam to run")
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument("--reference", action="store_true",
                      help=f"DPMFoam's histories from the case's {REFERENCE}, not a run")
    mode.add_argument("--write-reference", action="store_true",
                      help=f"write DPMFoam's histories to the case's {REFERENCE}")
    args = parser.parse_args(argv)
    try:
        return crosscheck(args)
    except CaseError as e:
        print(f"crosscheck: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
