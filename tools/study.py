#!/usr/bin/env python3
"""Batch studies over variants of a tutorial: one case copy per point, run through Dask.

    tools/study run TUTORIAL --set FILE:ENTRY=VALUES [--set ...] [--zip] [--model M1,M2]
                    [--spec study.toml] [--name NAME] [--out DIR] [--add]
                    [--scheduler ADDRESS] [--workers N] [--threads-per-point T]
                    [--reference NAME|none] [--compare COLUMN=NAME] [--retry-failed]
                    [--check] [--fsim PATH]
    tools/study table STUDY          rebuild STUDY/results.csv from the finished points
    tools/study plot STUDY --x COL --y COL [--hue COL] [--logx] [--logy] [--out PNG]

VALUES is a list `a,b,c`, a linear range `start:stop:count` or a geometric one
`log:start:stop:count`. The points are the Cartesian product of the --set axes, or with
--zip their element-wise pairs. Each entry is changed as `foamDictionary -entry ENTRY -set
VALUE` changes it (tools/foam_dict.py: nested `a/b/c` keys; comments and layout kept).

The whole sweep is checked before any point runs: every file and key must exist in the
tutorial (a missing last key only with --add), and `fsimFoam -dry-run` must accept every
point; otherwise each problem is named and the exit code is 2. Each point is a case copy
`<study>/point-NNNN/` with its parameters in `point.json`; it runs `fsimFoam -case DIR
-threads T` on a Dask worker and ends with `done.json` (written atomically), which makes it
final: running the same command again runs only the points without one. The results are in
`<study>/results.csv` (and `results.parquet` when pandas and pyarrow are importable).

Exit status: 0 when every point ran to its end, 1 when one or more failed (each is in the
table with its exit code and message), 2 for a bad sweep or set-up, 130 when interrupted.

The user guide is docs/user-guide/studies.md.
"""
import argparse
import contextlib
import csv
import datetime
import fcntl
import hashlib
import json
import math
import os
import re
import resource
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

TOOLS = Path(__file__).resolve().parent
ROOT = TOOLS.parent
if str(TOOLS) not in sys.path:
    sys.path.insert(0, str(TOOLS))

import foam_dict  # noqa: E402
import measured_run  # noqa: E402
import study_references  # noqa: E402
from measured_run import vm_hwm  # noqa: E402

CASE_DIRS = ("system", "constant", "0")
OUTPUT_PATTERNS = ("*.vtk", "*.vti", "*.vtu", "*.bin")
POINT = re.compile(r"point-(\d{4,})")
STDERR = "log.fsimFoam.stderr"
EXIT_BAD_INPUT, EXIT_FAILED, EXIT_INTERRUPTED = 2, 1, 130
TAIL_LINES = 20
# A run ended by one of these was stopped from outside (the study, a batch system's scancel),
# not failed: it writes no done.json and runs again on resume.
STOP_SIGNALS = (signal.SIGTERM, signal.SIGINT, signal.SIGHUP)


class StudyError(Exception):
    """A sweep or set-up that cannot run (exit 2); its message names every problem."""


# ----- the sweep ------------------------------------------------------------------------------

@dataclass
class Axis:
    file: str
    entry: str
    values: list
    column: str = ""

    @property
    def label(self):
        return f"{self.file}:{self.entry}"


_RANGE = re.compile(r"(log:)?([^:,]+):([^:,]+):(\d+)")


def format_number(x):
    """A range's value as a dictionary value: 12 significant digits, an integer as one."""
    return f"{x:.12g}"


def parse_values(text, where="--set"):
    """`a,b,c`, `start:stop:count` or `log:start:stop:count` -> the values as strings."""
    text = text.strip()
    m = _RANGE.fullmatch(text)
    if m:
        try:
            start, stop = float(m.group(2)), float(m.group(3))
        except ValueError:
            raise StudyError(f"{where}: range {text!r}: start and stop must be numbers")
        count = int(m.group(4))
        if count < 1:
            raise StudyError(f"{where}: range {text!r}: count must be at least 1")
        if m.group(1):
            if start <= 0 or stop <= 0:
                raise StudyError(f"{where}: range {text!r}: a log range needs positive ends")
            a, b = math.log(start), math.log(stop)
            values = [math.exp(a + (b - a) * k / (count - 1)) if count > 1 else start
                      for k in range(count)]
            values[-1] = stop if count > 1 else start
        else:
            values = [start + (stop - start) * k / (count - 1) if count > 1 else start
                      for k in range(count)]
        return [format_number(v) for v in values]
    values = [v.strip() for v in text.split(",")]
    if not text or any(v == "" for v in values):
        raise StudyError(f"{where}: empty value in {text!r}")
    return values


def toml_values(value, where):
    """A TOML value of a [set] entry: an array (each element one value) or a string in the
    command line's syntax (list or range)."""
    if isinstance(value, list):
        if not value:
            raise StudyError(f"{where}: no values")
        return [toml_scalar(v, where) for v in value]
    if isinstance(value, str):
        return parse_values(value, where)
    return [toml_scalar(value, where)]


def toml_scalar(v, where):
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, (int, float)):
        return format_number(v) if isinstance(v, float) else str(v)
    if isinstance(v, str):
        return v
    raise StudyError(f"{where}: value {v!r} is not a number or a string")


def parse_set(text):
    """`FILE:ENTRY=VALUES` -> Axis."""
    m = re.fullmatch(r"([^:=]+):([^=]+)=(.*)", text, re.S)
    if not m:
        raise StudyError(f"--set {text!r}: expected FILE:ENTRY=VALUES "
                         "(e.g. constant/transportProperties:nu=0.05,0.1)")
    return Axis(m.group(1).strip(), m.group(2).strip(),
                parse_values(m.group(3), f"--set {text!r}"))


def name_columns(axes):
    """Each axis's column in the table: its entry path, or FILE:ENTRY where two share one."""
    counts = {}
    for a in axes:
        counts[a.entry] = counts.get(a.entry, 0) + 1
    for a in axes:
        a.column = a.entry if counts[a.entry] == 1 else a.label


def sweep_points(axes, zipped):
    """The points as lists of (axis, value), in order: the Cartesian product (last axis
    fastest) or, with zipped, the element-wise pairs (an axis of one value in every point)."""
    if not axes:
        return [[]]
    if zipped:
        lengths = {len(a.values) for a in axes if len(a.values) > 1}
        if len(lengths) > 1:
            raise StudyError("--zip: the axes have different lengths: " + ", ".join(
                f"{a.label} {len(a.values)}" for a in axes))
        count = lengths.pop() if lengths else 1
        return [[(a, a.values[k if len(a.values) > 1 else 0]) for a in axes]
                for k in range(count)]
    points = [[]]
    for a in axes:
        points = [p + [(a, v)] for p in points for v in a.values]
    return points


# ----- the study's specification ------------------------------------------------------------

@dataclass
class Spec:
    tutorial: Path
    tutorial_name: str
    axes: list
    zipped: bool = False
    add: bool = False
    name: str = ""
    out: Path = None
    scheduler: str = None
    workers: int = None
    threads: int = None
    reference: str = None
    compare: dict = field(default_factory=dict)
    retry_failed: bool = False
    fsim: str = None


SPEC_KEYS = {"tutorial", "name", "out", "zip", "add", "model", "set", "compare", "reference",
             "scheduler", "workers", "threads_per_point", "retry_failed"}


def resolve_tutorial(text, base):
    """A tutorial folder's name (tutorials/<name>) or a path (relative to `base`)."""
    if "/" not in text and (ROOT / "tutorials" / text).is_dir():
        return (ROOT / "tutorials" / text).resolve()
    path = Path(text)
    path = path if path.is_absolute() else base / path
    if not path.is_dir():
        raise StudyError(f"tutorial {text!r}: no such folder (a name of tutorials/ or a path)")
    if not (path / "system").is_dir():
        raise StudyError(f"tutorial {text!r}: {path} has no system/ (not a case)")
    return path.resolve()


def build_spec(args):
    """The study from the command line and its --spec file (the command line wins)."""
    spec_file = {}
    base = Path.cwd()
    if args.spec:
        path = Path(args.spec)
        try:
            spec_file = tomllib.loads(path.read_text())
        except FileNotFoundError:
            raise StudyError(f"--spec {args.spec}: no such file")
        except tomllib.TOMLDecodeError as e:
            raise StudyError(f"--spec {args.spec}: {e}")
        unknown = set(spec_file) - SPEC_KEYS
        if unknown:
            raise StudyError(f"--spec {args.spec}: unknown key(s) {', '.join(sorted(unknown))} "
                             f"(known: {', '.join(sorted(SPEC_KEYS))})")
        base = path.resolve().parent
    tutorial_text = args.tutorial or spec_file.get("tutorial")
    if not tutorial_text:
        raise StudyError("no tutorial: give TUTORIAL or `tutorial = ...` in --spec")
    tutorial = resolve_tutorial(str(tutorial_text),
                                Path.cwd() if args.tutorial else base)

    axes = []
    for key, value in spec_file.get("set", {}).items():
        if ":" not in key:
            raise StudyError(f"--spec [set] {key!r}: expected \"FILE:ENTRY\" = values")
        file, entry = key.split(":", 1)
        axes.append(Axis(file.strip(), entry.strip(), toml_values(value, f"[set] {key!r}")))
    for text in args.set or []:
        axes.append(parse_set(text))
    models = args.model or spec_file.get("model")
    if models is not None:
        values = (parse_values(models, "--model") if isinstance(models, str)
                  else toml_values(models, "model"))
        axes.append(Axis("constant/couplingProperties", "model", values))
    seen = {}
    for a in axes:
        if a.label in seen:
            raise StudyError(f"{a.label} is swept twice")
        seen[a.label] = a
    name_columns(axes)
    for a in axes:
        if a.column in ("point", "status") or a.column in TABLE_RUN_COLUMNS:
            raise StudyError(f"{a.label}: its column {a.column!r} clashes with the table's own")

    compare = dict(spec_file.get("compare", {}))
    for text in args.compare or []:
        if "=" not in text:
            raise StudyError(f"--compare {text!r}: expected COLUMN=REFERENCE_NAME")
        column, ref = text.split("=", 1)
        compare[column.strip()] = ref.strip()

    name = args.name or spec_file.get("name") or (
        Path(args.spec).stem if args.spec else default_name(axes))
    if not re.fullmatch(r"[A-Za-z0-9_.+-]+", name):
        raise StudyError(f"--name {name!r}: use letters, digits and . _ + - only")
    out = args.out or spec_file.get("out")
    if out:
        out = Path(out)
        out = out if out.is_absolute() else (Path.cwd() if args.out else base) / out
    else:
        out = ROOT / "studies" / f"{tutorial.name}-{name}"
    threads = args.threads_per_point or spec_file.get("threads_per_point")
    workers = args.workers or spec_file.get("workers")
    scheduler = args.scheduler or spec_file.get("scheduler")
    if scheduler and args.workers:
        raise StudyError("--workers is for the local cluster; an existing cluster's workers "
                         "are its own (--scheduler)")
    if scheduler and not args.workers:
        workers = None
    for label, value in (("--threads-per-point", threads), ("--workers", workers)):
        if value is not None and (not isinstance(value, int) or value < 1):
            raise StudyError(f"{label} {value!r}: a positive whole number")
    reference = args.reference or spec_file.get("reference")
    return Spec(tutorial=tutorial, tutorial_name=tutorial.name, axes=axes,
                zipped=bool(args.zip or spec_file.get("zip", False)),
                add=bool(args.add or spec_file.get("add", False)), name=name,
                out=out.resolve(), scheduler=scheduler, workers=workers, threads=threads,
                reference=reference, compare=compare,
                retry_failed=bool(args.retry_failed or spec_file.get("retry_failed", False)),
                fsim=args.fsim)


def default_name(axes):
    if not axes:
        return "base"
    return "-".join(re.sub(r"[^A-Za-z0-9_.+-]", "_", a.entry.split("/")[-1]) for a in axes)


# ----- checking the sweep against the tutorial -----------------------------------------------

def check_axes(spec):
    """Every problem of the sweep's files and keys, as messages (empty when none)."""
    problems = []
    for a in spec.axes:
        where = f"--set {a.label}"
        rel = Path(a.file)
        if rel.is_absolute() or ".." in rel.parts:
            problems.append(f"{where}: the file must be a path inside the case")
            continue
        path = spec.tutorial / rel
        if not path.is_file():
            problems.append(f"{where}: {spec.tutorial_name} has no file {a.file}")
            continue
        if path.suffix == ".gz":
            problems.append(f"{where}: {a.file} is compressed; study changes text files only")
            continue
        text = path.read_text(errors="replace")
        keys = a.entry.split("/")
        if any(not k for k in keys):
            problems.append(f"{where}: empty keyword in {a.entry!r}")
            continue
        missing = None
        for k in range(1, len(keys) + 1):
            try:
                foam_dict.get_entry(text, "/".join(keys[:k]))
            except KeyError:
                missing = k
                break
        if missing is not None and missing < len(keys):
            problems.append(f"{where}: {a.file} has no entry {'/'.join(keys[:missing])!r}")
            continue
        if missing == len(keys) and not spec.add:
            problems.append(f"{where}: {a.file} has no entry {a.entry!r} (--add adds a "
                            "missing last keyword)")
            continue
        for value in a.values:
            try:
                foam_dict.set_entry(text, a.entry, value)
            except KeyError as e:
                problems.append(f"{where}: {a.file} has no dictionary to hold {e.args[0]!r}")
                break
            except ValueError as e:
                problems.append(f"{where}: {e}")
                break
    return problems


def case_files(tutorial):
    """The tutorial's case files (system/, constant/, 0/ less fsim's outputs), sorted."""
    files = []
    for top in CASE_DIRS:
        base = tutorial / top
        if not base.is_dir():
            continue
        for path in sorted(base.rglob("*")):
            if path.is_file() and not any(path.match(p) for p in OUTPUT_PATTERNS):
                files.append(path)
    return files


def case_hash(tutorial):
    h = hashlib.sha256()
    for path in case_files(tutorial):
        h.update(str(path.relative_to(tutorial)).encode() + b"\0")
        h.update(path.read_bytes() + b"\0")
    return h.hexdigest()[:16]


# ----- the study folder -----------------------------------------------------------------------

def write_json(path, data):
    """`path` replaced atomically (written beside it, flushed, renamed)."""
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    with open(tmp, "w") as f:
        json.dump(data, f, indent=2, allow_nan=True)
        f.write("\n")
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def read_json(path):
    try:
        return json.loads(Path(path).read_text())
    except (FileNotFoundError, json.JSONDecodeError):
        return None


@contextlib.contextmanager
def file_lock(path, blocking=True):
    """An exclusive flock on `path` (made when missing); yields False when not blocking and
    another process holds it."""
    fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | (0 if blocking else fcntl.LOCK_NB))
        except BlockingIOError:
            yield False
            return
        yield True
    finally:
        os.close(fd)


@dataclass
class Point:
    name: str
    dir: Path
    sets: list           # [(file, entry, value)]
    parameters: dict     # column -> value
    done: dict = None    # done.json, when final
    plan: dict = None    # from the dry run
    derived: dict = None  # measured and reference values, computed once

    @property
    def key(self):
        return frozenset((f, e, v) for f, e, v in self.sets)


def assign_points(spec, sweep, digest):
    """The sweep's points with their folders: a point whose parameters and tutorial files
    match an existing folder's point.json reuses it; the others get the next free numbers."""
    spec.out.mkdir(parents=True, exist_ok=True)
    existing, used = {}, set()
    for d in spec.out.iterdir():
        m = POINT.fullmatch(d.name)
        if not (m and d.is_dir()):
            continue
        used.add(int(m.group(1)))
        meta = read_json(d / "point.json")
        if meta and meta.get("case_hash") == digest:
            existing[frozenset(tuple(s) for s in meta["sets"])] = d
    points, next_free = [], 0
    for combo in sweep:
        sets = [(a.file, a.entry, v) for a, v in combo]
        point = Point("", None, sets, {a.column: v for a, v in combo})
        d = existing.pop(point.key, None)
        if d is None:
            while next_free in used:
                next_free += 1
            used.add(next_free)
            d = spec.out / f"point-{next_free:04d}"
        point.name, point.dir = d.name, d
        points.append(point)
    mine = {p.dir for p in points}
    stale = sum(1 for d in spec.out.iterdir()
                if POINT.fullmatch(d.name) and d not in mine and (d / "done.json").exists())
    return points, stale


def prepare_point(spec, point, digest, console):
    """A fresh case copy in the point's folder with its entries set and point.json. A point
    that an earlier study process still runs (on a cluster whose client was killed) is waited
    for; when that run ends with a done.json the point is final: returns False."""
    point.dir.mkdir(parents=True, exist_ok=True)
    with file_lock(point.dir / ".lock", blocking=False) as held:
        if not held:
            console.print(f"{point.name}: an earlier study process still runs it; waiting")
    with file_lock(point.dir / ".lock"):
        point.done = read_json(point.dir / "done.json")
        if point.done is not None:
            return False
        for child in point.dir.iterdir():
            if child.name == ".lock":
                continue
            if child.is_dir() and not child.is_symlink():
                shutil.rmtree(child)
            else:
                child.unlink()
        for path in case_files(spec.tutorial):
            dest = point.dir / path.relative_to(spec.tutorial)
            dest.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(path, dest)
        texts = {}
        for file, entry, value in point.sets:
            texts.setdefault(file, (point.dir / file).read_text())
            texts[file] = foam_dict.set_entry(texts[file], entry, value)
        for file, body in texts.items():
            (point.dir / file).write_text(body)
        write_json(point.dir / "point.json", {
            "name": point.name, "tutorial": spec.tutorial_name, "case_hash": digest,
            "parameters": point.parameters, "sets": [list(s) for s in point.sets]})
    return True


# ----- running one point (on a Dask worker: the standard library only) -----------------------

_PR_SET_PDEATHSIG = 1


def _die_with_parent():
    """The function a child runs before exec so that it gets SIGKILL when the thread that
    started it dies: a killed worker (or study) leaves no fsimFoam running. prctl is looked up
    here, in the parent, so that the child only calls it (no import or dlopen after fork in a
    threaded process). None where there is no prctl (not Linux)."""
    try:
        import ctypes
        prctl = ctypes.CDLL(None, use_errno=True).prctl
        prctl.argtypes = [ctypes.c_int] + [ctypes.c_ulong] * 4
        prctl.restype = ctypes.c_int
    except (OSError, AttributeError):
        return None
    kill = int(signal.SIGKILL)

    def setup():
        prctl(_PR_SET_PDEATHSIG, kill, 0, 0, 0)
    return setup


def _tail(path, lines=TAIL_LINES):
    try:
        with open(path, "rb") as f:
            f.seek(0, os.SEEK_END)
            f.seek(max(0, f.tell() - 16384))
            text = f.read().decode(errors="replace")
    except OSError:
        return []
    return [line for line in text.splitlines() if line.strip()][-lines:]


def error_message(stderr_lines):
    """The `fsimFoam: error:` line with what follows it, else the last lines."""
    for k, line in enumerate(stderr_lines):
        if "error:" in line:
            return "\n".join(stderr_lines[k:k + 6])
    return "\n".join(stderr_lines[-3:])


def _run_measured(cmd, case, stdout, stderr, env, stop_file=None):
    """Runs cmd; (exit code, wall s, cpu s, peak bytes, interrupted). Peak memory: the child's
    ru_maxrss when it exceeds this process's own (on Linux a child's ru_maxrss starts at its
    parent's high-water mark), else the highest VmHWM read from /proc while it ran."""
    start = time.perf_counter()
    # Its own session: a terminal's Ctrl-C reaches the study, which stops the runs itself.
    proc = subprocess.Popen(cmd, stdout=stdout, stderr=stderr, stdin=subprocess.DEVNULL,
                            env=env, preexec_fn=_die_with_parent(), start_new_session=True)
    peak = [0]
    interrupted = [False]
    finished = threading.Event()

    def watch():
        delay = 0.02
        while not finished.wait(delay):
            value = vm_hwm(proc.pid)
            if value:
                peak[0] = max(peak[0], value)
            if stop_file is not None and os.path.exists(stop_file) and not interrupted[0]:
                interrupted[0] = True
                with contextlib.suppress(ProcessLookupError):
                    os.kill(proc.pid, signal.SIGTERM)
            delay = min(1.0, delay * 1.5)

    watcher = threading.Thread(target=watch, daemon=True)
    watcher.start()
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    finished.set()
    watcher.join()
    proc.returncode = code = os.waitstatus_to_exitcode(status)
    own = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    child = usage.ru_maxrss * 1024
    peak_bytes = child if child > own else peak[0] or None
    return code, wall, usage.ru_utime + usage.ru_stime, peak_bytes, interrupted[0]


def summarize_monitors(case):
    """{<monitor>.<column>.final/.mean: value} of every monitor in case/postProcessing; mean
    is the time average (trapezoid over Time), the final row's value when there is one row.
    A partly written last line is left out."""
    out = {}
    base = Path(case) / "postProcessing"
    if not base.is_dir():
        return out
    for mon in sorted(p for p in base.iterdir() if p.is_dir()):
        starts = []
        for d in mon.iterdir():
            with contextlib.suppress(ValueError):
                if (d / f"{mon.name}.dat").is_file():
                    starts.append((float(d.name), d / f"{mon.name}.dat"))
        columns, rows = None, []
        for _, path in sorted(starts):
            for line in path.read_text(errors="replace").splitlines():
                if line.startswith("#"):
                    columns = columns or line.lstrip("#").split()
                    continue
                parts = line.split()
                if not parts or columns is None or len(parts) != len(columns):
                    continue
                try:
                    rows.append([float(v) for v in parts])
                except ValueError:
                    continue
        if not rows:
            continue
        t = [r[0] for r in rows] if columns[0] == "Time" else None
        for k, column in enumerate(columns):
            if column == "Time":
                continue
            values = [r[k] for r in rows]
            out[f"{mon.name}.{column}.final"] = values[-1]
            if t is not None and len(rows) > 1 and t[-1] > t[0]:
                area = sum(0.5 * (values[i] + values[i + 1]) * (t[i + 1] - t[i])
                           for i in range(len(rows) - 1))
                out[f"{mon.name}.{column}.mean"] = area / (t[-1] - t[0])
            else:
                out[f"{mon.name}.{column}.mean"] = sum(values) / len(values)
    return out


def _log_facts(log):
    """Steps (the `Time = ` blocks) and the `Peak memory = X MB` of an fsimFoam log."""
    steps, peak = 0, None
    with contextlib.suppress(OSError):
        with open(log, errors="replace") as f:
            for line in f:
                if line.startswith("Time = "):
                    steps += 1
                elif line.startswith("Peak memory = "):
                    with contextlib.suppress(ValueError):
                        peak = float(line.split("=")[1].split()[0]) * 1e6
    return steps, peak


def _utc_now():
    return datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="microseconds")


def dry_run_point(case, fsim, threads):
    """`fsimFoam -case CASE -dry-run -threads T`: exit code, message and the plan."""
    case = str(case)
    try:
        done = subprocess.run([fsim, "-case", case, "-dry-run", "-threads", str(threads)],
                              capture_output=True, text=True, stdin=subprocess.DEVNULL,
                              preexec_fn=_die_with_parent(), start_new_session=True)
    except OSError as e:
        return {"exit_code": None, "message": f"cannot run {fsim}: {e}"}
    plan = {"exit_code": done.returncode}
    if done.returncode != 0:
        lines = [line for line in done.stderr.splitlines() if line.strip()]
        plan["message"] = error_message(lines) or f"exit {done.returncode}"
    m = re.search(r"^Run time: about ([0-9.eE+-]+) s", done.stdout, re.M)
    plan["planned_wall_time"] = float(m.group(1)) if m else None
    m = re.search(r"^Steps\s*: about (\d+)", done.stdout, re.M)
    plan["planned_steps"] = int(m.group(1)) if m else None
    return plan


def run_point(case, fsim, threads, version="", stop_file=None):
    """Runs fsimFoam on one prepared point and writes its done.json (atomically) when the run
    ended, in success or failure; returns the record. A point with a done.json is returned as
    it is; one held by another process is waited for. A run stopped through `stop_file`, or
    one that could not start, writes no done.json (it runs again on resume)."""
    case = Path(case)
    with file_lock(case / ".lock"):
        previous = read_json(case / "done.json")
        if previous is not None:
            previous["reused"] = True
            return previous
        marker = case / "running.json"
        started = _utc_now()
        write_json(marker, {"host": socket.gethostname(), "pid": os.getpid(),
                            "started": started, "threads": threads})
        env = {**os.environ, "RAYON_NUM_THREADS": str(threads), "OMP_NUM_THREADS": "1"}
        record = {"status": "", "exit_code": None, "message": "", "started": started,
                  "host": socket.gethostname(), "pid": os.getpid(), "threads": threads,
                  "fsim_version": version}
        try:
            with open(case / "log.fsimFoam", "wb") as out, open(case / STDERR, "wb") as err:
                code, wall, cpu, peak, interrupted = _run_measured(
                    [fsim, "-case", str(case), "-threads", str(threads)], case, out, err,
                    env, stop_file)
        except OSError as e:
            marker.unlink(missing_ok=True)
            record.update(status="error", message=f"cannot run {fsim}: {e}")
            return record
        tail = _tail(case / STDERR)
        steps, logged_peak = _log_facts(case / "log.fsimFoam")
        if logged_peak and (peak is None or logged_peak > peak):
            peak = logged_peak
        record.update(exit_code=code, wall_time=wall, cpu_time=cpu,
                      peak_memory_mb=peak / 1e6 if peak else None,
                      finished=_utc_now(), stderr_tail=tail)
        monitors = summarize_monitors(case)
        record["steps"] = int(monitors.get("fluid.step.final", steps) or steps)
        record["monitors"] = monitors
        if interrupted or -code in STOP_SIGNALS:
            marker.unlink(missing_ok=True)
            record.update(status="interrupted", message="stopped by the study" if interrupted
                          else f"stopped by signal {-code} (SIGTERM, SIGINT or SIGHUP)")
            return record
        if code == 0:
            record["status"] = "done"
        else:
            record["status"] = "failed"
            record["message"] = (error_message(tail) if tail else "") or (
                f"killed by signal {-code}" if code < 0 else f"exit {code}")
        write_json(case / "done.json", record)
        marker.unlink(missing_ok=True)
        return record


# ----- threads and workers --------------------------------------------------------------------

def available_cores():
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


def plan_local(cores, points, workers=None, threads=None):
    """(workers, threads per point) of the local cluster: workers x threads <= cores."""
    if threads and threads > cores:
        raise StudyError(f"--threads-per-point {threads} exceeds the {cores} cores")
    if workers and threads:
        if workers * threads > cores:
            raise StudyError(f"--workers {workers} x --threads-per-point {threads} exceeds "
                             f"the {cores} cores")
    elif threads:
        workers = max(1, cores // threads)
    elif workers:
        if workers > cores:
            raise StudyError(f"--workers {workers} exceeds the {cores} cores")
        threads = max(1, cores // workers)
    else:
        workers = max(1, min(cores, points))
        threads = max(1, cores // workers)
    return max(1, min(workers, max(points, 1))), threads


def plan_cluster(workers, threads=None):
    """(threads per point, use the `cores` resource, concurrent points) on an existing cluster.
    `workers`: [{"nthreads", "resources", "host", "cores"}]. When every worker declares a
    `cores` resource, each point asks for T of them, so a worker runs at most cores/T points;
    otherwise each host's points (its workers' threads) x T must fit in its cores."""
    if not workers:
        raise StudyError("the cluster has no workers")
    if all("cores" in (w.get("resources") or {}) for w in workers):
        smallest = min(w["resources"]["cores"] for w in workers)
        threads = threads or 1
        if threads > smallest:
            raise StudyError(f"--threads-per-point {threads} exceeds the smallest worker's "
                             f"`cores` resource ({smallest:g})")
        slots = sum(min(w["nthreads"], int(w["resources"]["cores"] // threads))
                    for w in workers)
        return threads, True, max(1, slots)
    hosts = {}
    for w in workers:
        h = hosts.setdefault(w["host"], {"threads": 0, "cores": w["cores"]})
        h["threads"] += w["nthreads"]
    largest = min(max(1, h["cores"] // h["threads"]) for h in hosts.values())
    if threads and threads > largest:
        raise StudyError(
            f"--threads-per-point {threads}: the cluster's workers run "
            + ", ".join(f"{h['threads']} point(s) at once on {name}'s {h['cores']} cores"
                        for name, h in hosts.items())
            + f", so at most {largest} thread(s) a point fit; start the workers with "
            "fewer threads or declare cores (`dask worker --resources cores=N`)")
    return threads or largest, False, sum(w["nthreads"] for w in workers)


# ----- the results table ----------------------------------------------------------------------

TABLE_RUN_COLUMNS = ["status", "exit_code", "message", "wall_time", "cpu_time",
                     "peak_memory_mb", "steps", "threads", "planned_wall_time",
                     "planned_steps", "host", "started", "fsim_version"]


TEXT_COLUMNS = {"point", "status", "message", "host", "started", "fsim_version"}


def number_or_text(value):
    if isinstance(value, str):
        with contextlib.suppress(ValueError):
            return float(value)
    return value


def table_rows(points, reference_name, compare, warn=print):
    """The tidy table: one row per point, parameters first, then the run's columns, the
    monitors' final and mean values, measured values, references and errors."""
    ref = study_references.REFERENCES.get(reference_name) if reference_name else None
    pairs = dict(ref.compare) if ref else {}
    pairs.update(compare or {})
    rows, warned = [], set()
    for p in points:
        row = {"point": p.name}
        row.update(p.parameters)  # as written into the dictionaries
        rec = p.done or {}
        for column in TABLE_RUN_COLUMNS:
            row[column] = rec.get(column)
        if not rec:
            row["status"] = "pending"
        plan = p.plan or {}
        for column in ("planned_wall_time", "planned_steps"):
            if row.get(column) is None:
                row[column] = plan.get(column)
        if isinstance(row.get("message"), str):  # the first line: fsimFoam's error line
            row["message"] = row["message"].strip().split("\n")[0]
        row.update(rec.get("monitors", {}))
        if ref:
            row.update(_derived(p, ref, reference_name, warn, warned))
        for column, refname in pairs.items():
            measured = row.get(column)
            reference = row.get(f"reference.{refname}")
            error = math.nan
            if isinstance(measured, (int, float)) and isinstance(reference, (int, float)) \
                    and reference != 0 and not math.isnan(reference):
                error = abs(measured - reference) / abs(reference)
            row[f"error.{column}"] = error
        rows.append(row)
    return rows


def _derived(p, ref, reference_name, warn, warned):
    """The point's `measured.*` (once it is done) and `reference.*` values, computed once."""
    if p.derived is not None and (p.derived.get("_done") or not p.done):
        return {k: v for k, v in p.derived.items() if k != "_done"}
    out = {"_done": bool(p.done)}
    if ref.measure and p.done and p.done.get("status") == "done":
        try:
            out.update({f"measured.{k}": v for k, v in ref.measure(p.dir).items()})
        except Exception as e:  # the reference module's problem, not the run's
            if "measure" not in warned:
                warn(f"reference {reference_name}: measure failed on {p.name}: {e}")
                warned.add("measure")
    try:
        out.update({f"reference.{k}": v for k, v in ref.values(p.dir).items()})
    except Exception as e:
        if "values" not in warned:
            warn(f"reference {reference_name}: failed on {p.name}: {e}")
            warned.add("values")
    p.derived = out
    return {k: v for k, v in out.items() if k != "_done"}


def table_columns(rows, parameters):
    fixed = ["point"] + parameters + TABLE_RUN_COLUMNS
    rest = set()
    for r in rows:
        rest.update(k for k in r if k not in fixed)
    order = lambda k: ({"measured": 1, "reference": 2, "error": 3}.get(k.split(".")[0], 0), k)  # noqa: E731
    return fixed + sorted(rest, key=order)


def csv_value(v):
    if v is None:
        return ""
    if isinstance(v, float):
        return repr(v)
    return v


def write_table(folder, rows, columns, parquet=True):
    """results.csv (atomically) and, when pandas and pyarrow import, results.parquet."""
    tmp = folder / ".results.csv.tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for r in rows:
            w.writerow([csv_value(r.get(c)) for c in columns])
    os.replace(tmp, folder / "results.csv")
    if not parquet:
        return None
    try:
        import pandas as pd
        import pyarrow  # noqa: F401
    except ImportError:
        return None
    frame = pd.DataFrame([{c: r.get(c) for c in columns} for r in rows], columns=columns)
    for c in columns:
        try:  # numbers (parameters too, written as text) as float64, the rest as strings
            if c in TEXT_COLUMNS:
                raise ValueError
            frame[c] = pd.to_numeric(frame[c].replace("", None)).astype("float64")
        except (ValueError, TypeError):
            frame[c] = frame[c].astype("string")
    frame.to_parquet(folder / "results.parquet", index=False)
    return folder / "results.parquet"


def read_table(path):
    """results.csv as a list of dicts, numbers as floats."""
    with open(path, newline="") as f:
        return [{k: number_or_text(v) if v != "" else None for k, v in r.items()}
                for r in csv.DictReader(f)]


def finished_points(folder):
    """The rows of a study folder's results.csv whose point finished (status done)."""
    return [row for row in read_table(Path(folder) / "results.csv") if row["status"] == "done"]


# ----- the run ----------------------------------------------------------------------------------

def fsim_binary(given):
    """--fsim, else $FSIM, else fsimFoam on PATH, else the repository's release build
    (cargo build --release --bin fsimFoam first)."""
    for candidate in (given, os.environ.get("FSIM")):
        if candidate:
            path = Path(candidate).resolve()
            if not path.is_file():
                raise StudyError(f"fsimFoam {candidate}: no such file")
            return str(path)
    found = shutil.which("fsimFoam")
    if found:
        return str(Path(found).resolve())
    if shutil.which("cargo") is None:
        raise StudyError("no fsimFoam: give --fsim, set FSIM, or install cargo to build it")
    subprocess.run(["cargo", "build", "--release", "--quiet", "--bin", "fsimFoam"], cwd=ROOT,
                   check=True)
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    target = target if target.is_absolute() else ROOT / target
    return str(target / "release" / "fsimFoam")


def fsim_version(fsim):
    with contextlib.suppress(OSError, subprocess.SubprocessError):
        out = subprocess.run([fsim, "-version"], capture_output=True, text=True, timeout=30)
        return out.stdout.strip()
    return ""


class Cluster:
    """A Dask client on a local cluster of worker processes, or on --scheduler's cluster."""

    def __init__(self, spec, points, console):
        self.spec, self.points, self.console = spec, points, console
        self.local = None
        self.futures, self.running_dirs = [], []

    def __enter__(self):
        import logging

        import cloudpickle
        from distributed import Client, LocalCluster
        cloudpickle.register_pickle_by_value(sys.modules[__name__])
        cloudpickle.register_pickle_by_value(measured_run)
        if self.spec.scheduler:
            try:
                self.client = Client(self.spec.scheduler, timeout="30s")
            except (OSError, TimeoutError, ValueError) as e:
                raise StudyError(f"--scheduler {self.spec.scheduler}: {e}")
            if not self.client.scheduler_info()["workers"]:
                self.console.print(f"waiting for a worker of {self.spec.scheduler} …")
            self.client.wait_for_workers(1)
            info = self.client.scheduler_info()["workers"]
            cores = self.client.run(available_cores)
            hosts = self.client.run(socket.gethostname)
            workers = [{"nthreads": w["nthreads"], "resources": w.get("resources") or {},
                        "host": hosts.get(addr, w.get("host", addr)),
                        "cores": cores.get(addr, 1)} for addr, w in info.items()]
            self.threads, use_resources, self.slots = plan_cluster(workers, self.spec.threads)
            self.resources = {"cores": self.threads} if use_resources else None
            self.describe = (f"cluster {self.spec.scheduler}: {len(workers)} worker(s), "
                             f"{self.slots} point(s) at once, {self.threads} thread(s) each")
        else:
            cores = available_cores()
            n, self.threads = plan_local(cores, self.points, self.spec.workers,
                                         self.spec.threads)
            # The workers ignore SIGINT (a terminal's Ctrl-C reaches the whole process group):
            # the study stops them itself, without their tracebacks.
            previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
            try:
                self.local = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                          dashboard_address=":0", memory_limit=0,
                                          silence_logs=logging.ERROR)
            finally:
                signal.signal(signal.SIGINT, previous)
            self.client = Client(self.local)
            self.slots, self.resources = n, None
            self.describe = (f"local cluster: {n} worker(s) x {self.threads} thread(s) "
                             f"on {cores} cores")
        return self

    def submit(self, fn, *args, key, priority=0):
        return self.client.submit(_by_value(fn), *args, key=key, pure=False,
                                  priority=priority, resources=self.resources)

    def __exit__(self, *exc):
        with contextlib.suppress(Exception):
            self.client.close()
        if self.local is not None:
            with contextlib.suppress(Exception):
                self.local.close()
        return False


def _by_value(fn):
    """fn wrapped so that Dask sends it by value: a workers' Python need not import this
    module. (Dask pickles a task graph with pickle first, which would name `study.fn`; a
    closure makes it fall back to cloudpickle, which copies the functions of this module,
    registered with register_pickle_by_value.)"""
    def call(*args):
        return fn(*args)
    return call


def _key(spec, kind, point):
    return f"{kind}-{spec.tutorial_name}-{spec.name}-{point.name}-{os.urandom(4).hex()}"


class Progress:
    """The bar: points done, running, failed, the estimated time left (from the dry runs'
    planned times scaled by the finished points' measured over planned)."""

    def __init__(self, console, total, done, slots):
        from rich.progress import BarColumn, Progress as RichProgress, TextColumn, \
            TimeElapsedColumn
        self.total, self.slots = total, slots
        self.bar = RichProgress(
            TextColumn("[bold]{task.description}"), BarColumn(),
            TextColumn("{task.completed}/{task.total} done"),
            TextColumn("{task.fields[running]} running"),
            TextColumn("{task.fields[failed]} failed"),
            TextColumn("{task.fields[eta]}"), TimeElapsedColumn(),
            console=console, refresh_per_second=4)
        self.task = self.bar.add_task("study", total=total, completed=done, running=0,
                                      failed=0, eta="left ?")

    def update(self, done, running, failed, eta):
        text = "left ?" if eta is None else f"left {_duration(eta)}"
        self.bar.update(self.task, completed=done, running=running, failed=failed, eta=text)

    def __enter__(self):
        self.bar.start()
        return self

    def __exit__(self, *exc):
        self.bar.stop()


def _duration(seconds):
    seconds = max(0, int(round(seconds)))
    if seconds < 60:
        return f"{seconds} s"
    if seconds < 3600:
        return f"{seconds // 60} min {seconds % 60:02d} s"
    return f"{seconds // 3600} h {seconds % 3600 // 60:02d} min"


def estimate_left(pending, running_since, plans, ratios, slots, now):
    """Seconds left: the work of the points not finished (planned time x the median
    measured/planned ratio, less what the running ones have done) over the slots."""
    ratio = sorted(ratios)[len(ratios) // 2] if ratios else 1.0
    work = 0.0
    for name in pending:
        planned = plans.get(name)
        if planned is None:
            return None
        estimate = planned * ratio
        if name in running_since:
            estimate = max(0.0, estimate - (now - running_since[name]))
        work += estimate
    return work / max(1, min(slots, len(pending) or 1))


def point_label(point):
    return ", ".join(f"{k}={v}" for k, v in point.parameters.items()) or "as it is"


def choose_reference(spec):
    """The reference entry's name (or None), checked with the --compare names."""
    reference = spec.reference
    if reference is None and spec.tutorial_name in study_references.REFERENCES:
        reference = spec.tutorial_name
    if reference == "none":
        reference = None
    if reference and reference not in study_references.REFERENCES:
        raise StudyError(f"--reference {reference!r}: none such (tools/study_references.py "
                         f"has {', '.join(study_references.REFERENCES)})")
    if spec.compare and not reference:
        raise StudyError("--compare needs a reference (--reference NAME)")
    return reference


def check_references(reference, compare, points):
    """Every point's reference values computed before any run: the problems, as messages."""
    if not reference:
        return []
    ref = study_references.REFERENCES[reference]
    problems, names = [], None
    for p in points:
        try:
            values = ref.values(p.dir)
        except Exception as e:
            problems.append(f"{p.name} ({point_label(p)}): reference {reference}: "
                            f"{type(e).__name__}: {e}")
            continue
        names = names or set(values)
    if names is not None:
        for column, name in compare.items():
            if name not in names:
                problems.append(f"--compare {column}={name}: reference {reference} gives "
                                f"{', '.join(sorted(names))}")
    return problems


def run_study(spec, console, check_only=False):
    """The whole study; returns the exit code."""
    problems = check_axes(spec)
    if problems:
        raise StudyError("the sweep is wrong; no point ran:\n  " + "\n  ".join(problems))
    sweep = sweep_points(spec.axes, spec.zipped)
    reference = choose_reference(spec)
    fsim = fsim_binary(spec.fsim)
    version = fsim_version(fsim)
    digest = case_hash(spec.tutorial)

    spec.out.mkdir(parents=True, exist_ok=True)
    with file_lock(spec.out / ".study.lock", blocking=False) as held:
        if not held:
            raise StudyError(f"{spec.out}: another tools/study is running this study")
        (spec.out / "stop").unlink(missing_ok=True)
        points, stale = assign_points(spec, sweep, digest)
        for p in points:
            p.done = read_json(p.dir / "done.json")
            if p.done and spec.retry_failed and p.done.get("status") != "done":
                (p.dir / "done.json").unlink()
                p.done = None
        todo = [p for p in points if p.done is None]
        meta = {"tutorial": str(spec.tutorial.relative_to(ROOT))
                if spec.tutorial.is_relative_to(ROOT) else str(spec.tutorial),
                "tutorial_name": spec.tutorial_name, "name": spec.name,
                "case_hash": digest, "zip": spec.zipped, "add": spec.add,
                "axes": [{"file": a.file, "entry": a.entry, "column": a.column,
                          "values": a.values} for a in spec.axes],
                "reference": reference, "compare": spec.compare,
                "points": [p.name for p in points], "fsim_version": version,
                "updated": _utc_now()}
        console.print(f"study {spec.out} ({spec.tutorial_name}): {len(points)} point(s), "
                      f"{len(points) - len(todo)} finished before, {len(todo)} to run")
        if stale:
            console.print(f"note: {stale} finished point(s) of other parameters or of an "
                          "earlier version of the tutorial's files stay in the folder, "
                          "outside this table")
        todo = [p for p in todo if prepare_point(spec, p, digest, console)]
        problems = check_references(reference, spec.compare, points)
        if problems:
            raise StudyError("the references cannot be computed; no point ran:\n  "
                             + "\n  ".join(problems))
        write_json(spec.out / "study.json", meta)
        return _execute(spec, console, points, todo, fsim, version, reference, check_only)


def _execute(spec, console, points, todo, fsim, version, reference, check_only):
    parameters = [a.column for a in spec.axes]
    stop_file = str(spec.out / "stop")

    def save_table(parquet=False):
        rows = table_rows(points, reference, spec.compare, warn=console.print)
        write_table(spec.out, rows, table_columns(rows, parameters), parquet)

    if not todo:
        save_table(parquet=True)
        return _summary(console, spec, points)

    interrupted = False
    previous = signal.signal(signal.SIGTERM, _raise_interrupt)
    try:
        with Cluster(spec, len(todo), console) as cluster:
            console.print(cluster.describe)
            try:
                if not _dry_runs(spec, console, todo, fsim, cluster, check_only):
                    save_table()
                    return 0
                order = sorted(todo, key=lambda p: -((p.plan or {}).get("planned_wall_time")
                                                     or 0))
                futures = {cluster.submit(run_point, str(p.dir), fsim, cluster.threads,
                                          version, stop_file, key=_key(spec, "run", p),
                                          priority=len(order) - k): p
                           for k, p in enumerate(order)}
                _follow(console, points, futures, cluster, save_table)
            except KeyboardInterrupt:
                interrupted = True
                _stop_runs(stop_file, cluster)
    except KeyboardInterrupt:
        interrupted = True
    finally:
        signal.signal(signal.SIGTERM, previous)
    for p in points:
        if p.done is None:
            p.done = read_json(p.dir / "done.json")
    save_table(parquet=True)
    if interrupted:
        left = sum(1 for p in points if p.done is None)
        console.print(f"interrupted: {left} point(s) not finished; the same command resumes "
                      "the study")
        return EXIT_INTERRUPTED
    return _summary(console, spec, points)


def _dry_runs(spec, console, todo, fsim, cluster, check_only):
    """`fsimFoam -dry-run` of every point to run, before any runs: StudyError naming each
    point it rejects; False with --check (nothing to run)."""
    checks = {cluster.submit(dry_run_point, str(p.dir), fsim, cluster.threads,
                             key=_key(spec, "dry-run", p)): p
              for p in todo}
    console.print(f"checking {len(checks)} point(s) with fsimFoam -dry-run")
    rejected = []
    for future, p in checks.items():
        try:
            p.plan = future.result()
        except Exception as e:
            raise StudyError(f"the cluster could not run {p.name}'s dry run "
                             f"({type(e).__name__}: {e}); no point ran")
        if p.plan.get("exit_code") != 0:
            rejected.append(f"{p.name} ({point_label(p)}): "
                            + (p.plan.get("message") or "").replace("\n", "\n      "))
    if rejected:
        raise StudyError(f"fsimFoam -dry-run rejects {len(rejected)} of {len(checks)} "
                         "point(s); no point ran (their case copies are kept: "
                         "fsimFoam -case DIR -dry-run):\n  " + "\n  ".join(rejected))
    for p in checks.values():
        meta = read_json(p.dir / "point.json") or {}
        meta["plan"] = {k: p.plan.get(k) for k in ("planned_wall_time", "planned_steps")}
        write_json(p.dir / "point.json", meta)
    if check_only:
        planned = sum(p.plan.get("planned_wall_time") or 0 for p in checks.values())
        console.print(f"checked: fsimFoam -dry-run accepts the {len(checks)} point(s) to run "
                      f"({_duration(planned)} of runs planned); --check runs none")
        return False
    return True


def _stop_runs(stop_file, cluster, wait=10.0):
    """Asks the running points to stop (their fsimFoam gets SIGTERM within a second, and
    they write no done.json), cancels the queued ones, and waits a little for both."""
    Path(stop_file).touch()
    futures = list(cluster.futures)
    with contextlib.suppress(Exception):
        cluster.client.cancel([f for f in futures if not f.done()])
    deadline = time.monotonic() + wait
    while time.monotonic() < deadline and any(
            Path(p, "running.json").exists() for p in cluster.running_dirs):
        time.sleep(0.2)


def _raise_interrupt(signum, frame):
    raise KeyboardInterrupt


def _follow(console, points, futures, cluster, save_table):
    """Waits for the runs, with the progress bar; a line per finished point."""
    pending = dict(futures)
    cluster.futures = list(futures)
    cluster.running_dirs = [p.dir for p in futures.values()]
    finished = sum(1 for p in points if p.done is not None)
    failed = sum(1 for p in points if p.done and p.done.get("status") != "done")
    plans = {p.name: (p.plan or {}).get("planned_wall_time") for p in futures.values()}
    ratios, running_since = [], {}
    last_scan = 0.0
    with Progress(console, len(points), finished, cluster.slots) as bar:
        while pending:
            now = time.monotonic()
            ready = [f for f in pending if f.done()]
            for future in ready:
                p = pending.pop(future)
                running_since.pop(p.name, None)
                if future.status == "finished":
                    rec = future.result()
                else:
                    try:
                        error = future.exception()
                    except BaseException as e:  # cancelled
                        error = e
                    rec = {"status": "error", "message": f"{type(error).__name__}: {error}"}
                if rec.get("status") in ("done", "failed"):
                    p.done = rec
                    finished += 1
                    failed += rec["status"] == "failed"
                    if plans.get(p.name) and rec.get("wall_time") and not rec.get("reused"):
                        ratios.append(rec["wall_time"] / plans[p.name])
                    first = (rec.get("message") or "").splitlines()[:1]
                    detail = (f"{rec.get('wall_time') or 0:.1f} s" if rec["status"] == "done"
                              else f"exit {rec.get('exit_code')}"
                              + (f": {first[0]}" if first else ""))
                    console.print(f"{p.name} {rec['status']} ({point_label(p)}): {detail}")
                else:
                    console.print(f"{p.name} {rec.get('status')} ({point_label(p)}): "
                                  f"{rec.get('message')}; it runs again on resume")
                save_table()
            if now - last_scan > 1.0 or ready:
                last_scan = now
                for p in pending.values():
                    if p.name not in running_since and (p.dir / "running.json").exists():
                        running_since[p.name] = now
            eta = estimate_left([p.name for p in pending.values()], running_since, plans,
                                ratios, cluster.slots, now)
            bar.update(finished, len(running_since), failed, eta)
            if not ready:
                time.sleep(0.2)


def _summary(console, spec, points):
    failed = [p for p in points if p.done and p.done.get("status") != "done"]
    not_run = [p for p in points if p.done is None]
    console.print(f"{len(points) - len(failed) - len(not_run)} of {len(points)} point(s) "
                  f"done, {len(failed)} failed, {len(not_run)} not run; table "
                  f"{spec.out / 'results.csv'}")
    for p in failed:
        first = (p.done.get("message") or "").splitlines()[:1]
        console.print(f"  {p.name} ({point_label(p)}): exit {p.done.get('exit_code')}"
                      + (f": {first[0]}" if first else ""))
    return EXIT_FAILED if failed or not_run else 0


# ----- table and plot commands -----------------------------------------------------------------

def study_folder(text):
    path = Path(text)
    if not path.is_dir() and (ROOT / "studies" / text).is_dir():
        path = ROOT / "studies" / text
    if not (path / "study.json").is_file():
        raise StudyError(f"{text}: not a study folder (no study.json)")
    return path.resolve()


def rebuild_table(folder, console):
    meta = read_json(folder / "study.json")
    points = []
    for name in meta["points"]:
        info = read_json(folder / name / "point.json") or {}
        p = Point(name, folder / name, [tuple(s) for s in info.get("sets", [])],
                  info.get("parameters", {}), read_json(folder / name / "done.json"),
                  info.get("plan"))
        points.append(p)
    rows = table_rows(points, meta.get("reference"), meta.get("compare"),
                      warn=console.print)
    write_table(folder, rows, table_columns(rows, [a["column"] for a in meta["axes"]]))
    console.print(f"{folder / 'results.csv'}: {len(rows)} point(s)")
    return 0


def plot(folder, x, y, hue=None, logx=False, logy=False, out=None):
    """y against x from results.csv (finished points), one line per value of hue."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = read_table(folder / "results.csv")
    if not rows:
        raise StudyError(f"{folder / 'results.csv'}: no rows")
    for column in (x, y, hue):
        if column and column not in rows[0]:
            raise StudyError(f"no column {column!r}; the table has: {', '.join(rows[0])}")
    rows = [r for r in rows if r.get("status") == "done" and r.get(x) is not None
            and isinstance(r.get(y), float) and not math.isnan(r[y])]
    if not rows:
        raise StudyError(f"no finished point has both {x} and {y}")
    categorical = not all(isinstance(r[x], float) for r in rows)
    categories = sorted({str(r[x]) for r in rows}) if categorical else None
    groups = {}
    for r in rows:
        groups.setdefault(r.get(hue) if hue else None, []).append(r)
    fig, ax = plt.subplots(figsize=(6.4, 4.4), constrained_layout=True)
    for value, members in sorted(groups.items(), key=lambda kv: str(kv[0])):
        xs = [categories.index(str(r[x])) if categorical else r[x] for r in members]
        pairs = sorted(zip(xs, (r[y] for r in members)))
        label = None if hue is None else f"{hue} = {value:g}" if isinstance(value, float) \
            else f"{hue} = {value}"
        ax.plot([a for a, _ in pairs], [b for _, b in pairs], "o-", label=label)
    if categorical:
        ax.set_xticks(range(len(categories)), categories)
    if logx and not categorical:
        ax.set_xscale("log")
    if logy:
        ax.set_yscale("log")
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    meta = read_json(folder / "study.json") or {}
    ax.set_title(f"{meta.get('tutorial_name', '')} study {meta.get('name', folder.name)}",
                 fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    if hue:
        ax.legend(fontsize=9)
    safe = lambda s: re.sub(r"[^A-Za-z0-9_.+-]", "_", s)  # noqa: E731
    out = Path(out) if out else folder / f"{safe(y)}-vs-{safe(x)}.png"
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


# ----- command line -----------------------------------------------------------------------------

def parser():
    top = argparse.ArgumentParser(
        prog="tools/study", description="Batch studies over variants of a tutorial "
        "(docs/user-guide/studies.md).")
    sub = top.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run a study (resumes a killed one)")
    run.add_argument("tutorial", nargs="?",
                     help="a folder name of tutorials/ or a case path (or `tutorial` in --spec)")
    run.add_argument("--set", action="append", metavar="FILE:ENTRY=VALUES",
                     help="an axis: a,b,c or start:stop:count or log:start:stop:count")
    run.add_argument("--zip", action="store_true", help="pair the axes instead of crossing them")
    run.add_argument("--model", metavar="M1,M2",
                     help="shorthand for --set constant/couplingProperties:model=M1,M2")
    run.add_argument("--add", action="store_true",
                     help="add an entry whose last keyword is missing (its parent must exist)")
    run.add_argument("--spec", metavar="TOML", help="the study in a TOML file")
    run.add_argument("--name", help="the study's name (default: the swept keywords)")
    run.add_argument("--out", help="the study folder (default: studies/<tutorial>-<name>)")
    run.add_argument("--scheduler", metavar="ADDRESS",
                     help="an existing Dask scheduler (tcp://host:port); default a local "
                     "cluster")
    run.add_argument("--workers", type=int, help="local cluster: points at once")
    run.add_argument("--threads-per-point", type=int, metavar="T",
                     help="fsimFoam -threads for each point")
    run.add_argument("--reference", help="the entry of tools/study_references.py (default: "
                     "the tutorial's name when it has one; `none` for none)")
    run.add_argument("--compare", action="append", metavar="COLUMN=NAME",
                     help="compare a table column with a reference value")
    run.add_argument("--retry-failed", action="store_true",
                     help="run the points that failed before again")
    run.add_argument("--check", action="store_true",
                     help="check the sweep and dry-run the points, run none")
    run.add_argument("--fsim", help="the fsimFoam to run (default $FSIM, PATH, or a build)")

    table = sub.add_parser("table", help="rebuild STUDY/results.csv from its points")
    table.add_argument("study")
    pl = sub.add_parser("plot", help="a chart from STUDY/results.csv")
    pl.add_argument("study")
    pl.add_argument("--x", required=True)
    pl.add_argument("--y", required=True)
    pl.add_argument("--hue")
    pl.add_argument("--logx", action="store_true")
    pl.add_argument("--logy", action="store_true")
    pl.add_argument("--out", metavar="PNG")
    return top


def main(argv=None):
    from rich.console import Console
    args = parser().parse_args(argv)
    console = Console(stderr=True, highlight=False, markup=False, soft_wrap=True)
    try:
        if args.command == "run":
            return run_study(build_spec(args), console, check_only=args.check)
        folder = study_folder(args.study)
        if args.command == "table":
            return rebuild_table(folder, console)
        out = plot(folder, args.x, args.y, args.hue, args.logx, args.logy, args.out)
        console.print(f"wrote {out}")
        return 0
    except StudyError as e:
        console.print(f"tools/study: error: {e}", markup=False)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        console.print("tools/study: interrupted")
        return EXIT_INTERRUPTED


if __name__ == "__main__":
    # Run as the module `study`, so that Dask's workers receive its functions by value.
    import study
    sys.exit(study.main())
