"""tools/study: sweeps, the checks before any point runs, a real Dask cluster on loopback,
resuming a killed study, failed points in the table, and the pieces (values, thread plans,
monitor summaries, references)."""
import csv
import datetime
import json
import math
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import study
import study_references

ROOT = Path(__file__).resolve().parents[2]
TOOLS = ROOT / "tools"
PYTHON = sys.executable
# The grid's second-order Laplacian decays the k = 1 vortex at nu k_h^2, k_h^2 = 1 - h^2/12,
# h = 2 pi / 32 (tutorials/taylorGreen/README.md).
H = 2 * math.pi / 32
RATE_FACTOR = 1 - H * H / 12


def run_study(args, **kw):
    return subprocess.run([PYTHON, str(TOOLS / "study.py"), *map(str, args)],
                          capture_output=True, text=True, **kw)


def table(folder):
    with open(folder / "results.csv", newline="") as f:
        return list(csv.DictReader(f))


def ran(point):
    """Whether fsimFoam ran in a point folder (a log, a done.json or a time directory)."""
    return (point / "log.fsimFoam").exists() or (point / "done.json").exists() or any(
        p.is_dir() and p.name != "0" and p.name[0].isdigit() for p in point.iterdir())


# ----- the pieces ------------------------------------------------------------------------------

def test_values_lists_ranges_and_log_ranges():
    assert study.parse_values("a, b,c") == ["a", "b", "c"]
    assert study.parse_values("0.05:0.2:4") == ["0.05", "0.1", "0.15", "0.2"]
    assert study.parse_values("log:1e-3:1e-1:3") == ["0.001", "0.01", "0.1"]
    assert study.parse_values("14:56:4") == ["14", "28", "42", "56"]
    assert study.parse_values("(0.02 0 0)") == ["(0.02 0 0)"]
    for bad in ("", "a,,b", "log:0:1:3", "x:1:2"):
        with pytest.raises(study.StudyError):
            study.parse_values(bad)


def test_product_and_zip():
    a = study.Axis("f", "a", ["1", "2"], "a")
    b = study.Axis("f", "b", ["x", "y", "z"], "b")
    product = study.sweep_points([a, b], zipped=False)
    assert [[v for _, v in p] for p in product] == [
        ["1", "x"], ["1", "y"], ["1", "z"], ["2", "x"], ["2", "y"], ["2", "z"]]
    with pytest.raises(study.StudyError, match="different lengths"):
        study.sweep_points([a, b], zipped=True)
    c = study.Axis("f", "c", ["u", "v"], "c")
    assert [[v for _, v in p] for p in study.sweep_points([a, c], zipped=True)] == [
        ["1", "u"], ["2", "v"]]
    one = study.Axis("f", "one", ["w"], "one")
    assert [[v for _, v in p] for p in study.sweep_points([a, one, c], zipped=True)] == [
        ["1", "w", "u"], ["2", "w", "v"]]


def test_threads_never_oversubscribe_the_cores():
    assert study.plan_local(2, points=8) == (2, 1)
    assert study.plan_local(2, points=1) == (1, 2)
    assert study.plan_local(8, points=8, threads=2) == (4, 2)
    assert study.plan_local(8, points=8, workers=2) == (2, 4)
    for kw in ({"workers": 3, "threads": 3}, {"threads": 9}, {"workers": 9}):
        with pytest.raises(study.StudyError):
            study.plan_local(8, points=8, **kw)
    # An existing cluster: two one-thread workers on a 2-core host (the test below).
    two = [{"nthreads": 1, "resources": {}, "host": "h", "cores": 2}] * 2
    assert study.plan_cluster(two) == (1, False, 2)
    with pytest.raises(study.StudyError, match="resources cores"):
        study.plan_cluster(two, threads=2)
    # Workers that declare cores: each point asks for T of them.
    node = [{"nthreads": 32, "resources": {"cores": 32}, "host": "n1", "cores": 32}]
    assert study.plan_cluster(node, threads=4) == (4, True, 8)
    with pytest.raises(study.StudyError):
        study.plan_cluster(node, threads=64)


def test_monitor_summary_is_final_and_time_average(tmp_path):
    mon = tmp_path / "postProcessing" / "probe" / "0"
    mon.mkdir(parents=True)
    # v = t on 0..1 then 1 on 1..3: time average (0.5 + 2) / 3; a half-written last row.
    (mon / "probe.dat").write_text("# Time\tv\tw\n0 0 5\n1 1 5\n3 1 5\n3.5 2")
    summary = study.summarize_monitors(tmp_path)
    assert summary["probe.v.final"] == 1
    assert summary["probe.v.mean"] == pytest.approx(2.5 / 3)
    assert summary["probe.w.mean"] == 5
    assert "probe.Time.final" not in summary


def test_table_files(tmp_path):
    """results.csv round trip; results.parquet (numbers as float64) where pandas and pyarrow
    import (they are not dependencies: skipped without them)."""
    rows = [{"point": "point-0000", "nu": "0.1", "status": "done", "message": "",
             "wall_time": 1.5, "fluid.kineticEnergy.final": 0.03},
            {"point": "point-0001", "nu": "0.2", "status": "failed", "exit_code": 1,
             "message": "fsimFoam: error: a, b", "wall_time": 0.25}]
    columns = study.table_columns(rows, ["nu"])
    assert columns[:4] == ["point", "nu", "status", "exit_code"]
    study.write_table(tmp_path, rows, columns, parquet=False)
    back = study.read_table(tmp_path / "results.csv")
    assert back[1]["message"] == "fsimFoam: error: a, b" and back[1]["exit_code"] == 1
    assert back[0]["nu"] == 0.1 and back[0]["fluid.kineticEnergy.final"] == 0.03
    assert back[1]["fluid.kineticEnergy.final"] is None
    pd = pytest.importorskip("pandas")
    pytest.importorskip("pyarrow")
    assert study.write_table(tmp_path, rows, columns) == tmp_path / "results.parquet"
    frame = pd.read_parquet(tmp_path / "results.parquet")
    assert frame["nu"].tolist() == [0.1, 0.2] and frame["nu"].dtype == "float64"
    assert frame["message"].tolist() == ["", "fsimFoam: error: a, b"]


def test_references_of_the_tutorials_match_their_readmes():
    tutorials = ROOT / "tutorials"
    refs = study_references.REFERENCES
    assert refs["porousMedia"].values(tutorials / "porousMedia")["K"] == pytest.approx(
        3.6418, abs=1e-4)
    sphere = refs["settlingSphere"].values(tutorials / "settlingSphere")
    assert sphere["settlingVelocity"] / sphere["stokesVelocity"] == pytest.approx(
        0.41314, abs=1e-5)
    bead = refs["settlingInLiquid"].values(tutorials / "settlingInLiquid")
    assert bead["settlingVelocity"] == pytest.approx(0.14595, abs=1e-5)
    assert refs["channel"].values(tutorials / "channel")["drivingGradient"] == pytest.approx(
        1.2e-4)
    tg = refs["taylorGreen"].values(tutorials / "taylorGreen")
    assert tg["kineticEnergy"] == pytest.approx(0.25 * math.exp(-2))


def test_spec_file_and_command_line_make_one_study(tmp_path):
    spec = tmp_path / "nu.toml"
    spec.write_text('tutorial = "taylorGreen"\nzip = true\n'
                    '[set]\n"constant/transportProperties:nu" = [0.05, 0.1]\n'
                    '"system/controlDict:deltaT" = "0.01:0.02:2"\n'
                    '[compare]\n"fluid.kineticEnergy.mean" = "kineticEnergy"\n')
    args = study.parser().parse_args(["run", "--spec", str(spec), "--set",
                                      "system/controlDict:endTime=1,2,3"])
    with pytest.raises(study.StudyError, match="different lengths"):
        study.sweep_points(study.build_spec(args).axes, zipped=True)
    args = study.parser().parse_args(["run", "--spec", str(spec)])
    s = study.build_spec(args)
    assert s.tutorial == ROOT / "tutorials" / "taylorGreen" and s.name == "nu"
    assert s.out == ROOT / "studies" / "taylorGreen-nu"
    assert [(a.column, a.values) for a in s.axes] == [("nu", ["0.05", "0.1"]),
                                                      ("deltaT", ["0.01", "0.02"])]
    assert s.zipped and s.compare == {"fluid.kineticEnergy.mean": "kineticEnergy"}
    spec.write_text('tutorial = "taylorGreen"\nthreads = 2\n')
    with pytest.raises(study.StudyError, match="unknown key"):
        study.build_spec(study.parser().parse_args(["run", "--spec", str(spec)]))


# ----- whole studies -----------------------------------------------------------------------------

@pytest.fixture
def loopback_cluster(tmp_path):
    """A Dask scheduler and two one-thread workers on 127.0.0.1, as separate processes."""
    dask = Path(PYTHON).parent / "dask"
    scheduler_file = tmp_path / "scheduler.json"
    logs = []

    def start(args, log):
        logs.append(open(tmp_path / log, "w"))
        return subprocess.Popen([str(dask), *args], stdout=subprocess.DEVNULL,
                                stderr=logs[-1])

    # Port 0: the scheduler picks a free port and writes its address to the file.
    procs = [start(["scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                    "--scheduler-file", str(scheduler_file)], "scheduler.log")]
    try:
        deadline = time.monotonic() + 60
        while not scheduler_file.exists() and time.monotonic() < deadline:
            time.sleep(0.1)
        address = json.loads(scheduler_file.read_text())["address"]
        assert address.startswith("tcp://127.0.0.1:")
        for k in range(2):
            procs.append(start(["worker", address, "--nworkers", "1", "--nthreads", "1",
                                "--no-dashboard"], f"worker{k}.log"))
        from distributed import Client
        with Client(address, timeout="30s") as client:
            client.wait_for_workers(2, timeout=60)
        yield address
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in reversed(procs):
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
        for log in logs:
            log.close()


def test_a_study_on_a_dask_cluster_on_loopback(fsim, loopback_cluster, tmp_path):
    """Eight Taylor-Green points (nu x deltaT) through `tools/study run --scheduler`: each
    point's energy decays at 4 nu k_h^2/k^2, the grid's rate, and the table says so."""
    out = tmp_path / "tg"
    started = time.monotonic()
    done = subprocess.run(
        [str(TOOLS / "study"), "run", "taylorGreen",
         "--set", "constant/transportProperties:nu=0.05:0.2:4",
         "--set", "system/controlDict:deltaT=0.01,0.02",
         "--scheduler", loopback_cluster, "--out", str(out), "--fsim", str(fsim)],
        capture_output=True, text=True, timeout=300)
    elapsed = time.monotonic() - started
    assert done.returncode == 0, done.stderr
    assert "2 worker(s), 2 point(s) at once, 1 thread(s) each" in done.stderr
    rows = table(out)
    assert len(rows) == 8
    assert [(float(r["nu"]), float(r["deltaT"])) for r in rows] == [
        (nu, dt) for nu in (0.05, 0.1, 0.15, 0.2) for dt in (0.01, 0.02)]
    pids = set()
    for r in rows:
        nu, dt = float(r["nu"]), float(r["deltaT"])
        assert r["status"] == "done" and r["exit_code"] == "0" and r["message"] == ""
        assert int(r["threads"]) == 1
        assert int(r["steps"]) == round(5 / dt) == int(r["planned_steps"])
        assert 0 < float(r["cpu_time"]) and 0 < float(r["wall_time"]) < elapsed
        assert 2 < float(r["peak_memory_mb"]) < 100
        # The decay rate against the exact 4 nu: the grid's factor, within RK3's time error.
        rate = float(r["measured.decayRate"])
        assert float(r["reference.decayRate"]) == pytest.approx(4 * nu)
        assert rate / (4 * nu) == pytest.approx(RATE_FACTOR, abs=2e-4)
        assert float(r["error.measured.decayRate"]) == pytest.approx(1 - rate / (4 * nu))
        # The final energy against E0 exp(-4 nu T): off by the rate's error times 4 nu T.
        energy = float(r["fluid.kineticEnergy.final"])
        assert float(r["reference.kineticEnergy"]) == pytest.approx(0.25 * math.exp(-20 * nu))
        assert float(r["error.fluid.kineticEnergy.final"]) == pytest.approx(
            20 * nu * (1 - RATE_FACTOR), rel=0.1)
        assert energy == pytest.approx(0.25 * math.exp(-20 * nu * RATE_FACTOR), rel=2e-4)
        record = json.loads((out / r["point"] / "done.json").read_text())
        assert record["status"] == "done" and not (out / r["point"] / "running.json").exists()
        pids.add(record["pid"])
        params = json.loads((out / r["point"] / "point.json").read_text())["parameters"]
        assert params == {"nu": r["nu"], "deltaT": r["deltaT"]}
        assert f"nu              {r['nu']};" in (
            out / r["point"] / "constant/transportProperties").read_text()
    assert len(pids) == 2, "both workers ran points"

    # The table again from the points, and a chart from it.
    assert run_study(["table", out]).returncode == 0
    assert table(out) == rows
    png = tmp_path / "rate.png"
    drawn = run_study(["plot", out, "--x", "nu", "--y", "error.fluid.kineticEnergy.final",
                       "--hue", "deltaT", "--logy", "--out", png])
    assert drawn.returncode == 0, drawn.stderr
    assert png.stat().st_size > 10_000


def fsim_processes_in(folder):
    import psutil
    found = []
    for proc in psutil.process_iter(["name", "cmdline"]):
        with_folder = any(str(folder) in part for part in (proc.info["cmdline"] or []))
        if with_folder and proc.info["name"] == "fsimFoam":
            found.append(proc.pid)
    return found


def start_and_stop(args, out, finished, how):
    """Starts a study and sends it `how` once `finished` points have a done.json and the next
    one is running; (exit code, when, the point it stopped midway)."""
    proc = subprocess.Popen([PYTHON, str(TOOLS / "study.py"), *map(str, args)],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 180

    def running():
        return [p.parent for p in out.glob("point-*/running.json")
                if not (p.parent / "done.json").exists()]

    while len(list(out.glob("point-*/done.json"))) < finished or not running():
        assert proc.poll() is None, proc.stderr.read()
        assert time.monotonic() < deadline
        time.sleep(0.02)
    time.sleep(0.3)  # into its fsimFoam run (about a second)
    midway = running()
    assert len(midway) == 1
    proc.send_signal(how)
    at = time.time()
    code = proc.wait(timeout=60)
    proc.stderr.close()
    # Nothing of the stopped study runs on: its fsimFoam end with it, unfinished.
    deadline = time.monotonic() + 5
    while fsim_processes_in(out) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert fsim_processes_in(out) == []
    assert not (midway[0] / "done.json").exists()
    log = (midway[0] / "log.fsimFoam").read_text()
    assert "Time = " in log and "\nEnd" not in log, "its fsimFoam was stopped midway"
    return code, at


def finished_records(out):
    return {p.parent.name: (p.read_bytes(), p.stat().st_mtime_ns)
            for p in out.glob("point-*/done.json")}


def test_a_killed_study_resumes_with_the_unfinished_points_only(fsim, tmp_path):
    """Five points one at a time: stopped with SIGTERM, then killed with SIGKILL, each time
    midway; each rerun runs only the points without a done.json, and leaves the others'
    untouched."""
    out = tmp_path / "tg"
    args = ["run", "taylorGreen", "--set", "system/controlDict:endTime=20",
            "--set", "constant/transportProperties:nu=0.02:0.06:5", "--workers", "1",
            "--out", out, "--fsim", fsim]
    code, _ = start_and_stop(args, out, 1, signal.SIGTERM)
    assert code == study.EXIT_INTERRUPTED
    first = finished_records(out)
    assert 1 <= len(first) < 5
    code, killed_at = start_and_stop(args, out, len(first) + 1, signal.SIGKILL)
    assert code == -signal.SIGKILL
    second = finished_records(out)
    assert all(second[name] == first[name] for name in first)
    assert len(first) < len(second) < 5

    done = run_study(args, timeout=300)
    assert done.returncode == 0, done.stderr
    assert f"{len(second)} finished before, {5 - len(second)} to run" in done.stderr
    last = finished_records(out)
    assert len(last) == 5
    for name, (data, mtime) in last.items():
        record = json.loads(data)
        if name in second:
            assert (data, mtime) == second[name]
        else:  # run by the last command, after the kill
            assert datetime.datetime.fromisoformat(record["started"]).timestamp() > killed_at
    rows = table(out)
    assert [r["status"] for r in rows] == ["done"] * 5
    assert all(not (out / r["point"] / "running.json").exists() for r in rows)


def test_a_bad_sweep_is_named_before_any_point_runs(fsim, tmp_path):
    out = tmp_path / "bad"
    bad_keys = run_study(["run", "taylorGreen",
                          "--set", "constant/nope:nu=1",
                          "--set", "constant/transportProperties:foo/bar=1",
                          "--set", "constant/transportProperties:nuu=0.1,0.2",
                          "--set", "constant/transportProperties:nu=0.1",
                          "--out", out, "--fsim", fsim])
    assert bad_keys.returncode == 2
    for text in ("taylorGreen has no file constant/nope",
                 "constant/transportProperties has no entry 'foo'",
                 "constant/transportProperties has no entry 'nuu' (--add"):
        assert text in bad_keys.stderr
    assert not out.exists()

    # --add adds a missing last keyword; the parent must exist all the same.
    added = run_study(["run", "taylorGreen", "--add", "--check",
                       "--set", "system/controlDict:writeFormat=ascii",
                       "--out", tmp_path / "added", "--fsim", fsim])
    assert added.returncode == 0, added.stderr
    copy = tmp_path / "added" / "point-0000"
    assert "writeFormat ascii;" in (copy / "system/controlDict").read_text()
    assert not ran(copy)

    rejected = run_study(["run", "taylorGreen",
                          "--set", "constant/transportProperties:nu=0.1,-1",
                          "--set", "system/controlDict:deltaT=0.02,0.5",
                          "--out", out, "--fsim", fsim])
    assert rejected.returncode == 2
    assert "fsimFoam -dry-run rejects 3 of 4 point(s); no point ran" in rejected.stderr
    assert ("point-0002 (nu=-1, deltaT=0.02): fsimFoam: error: "
            "constant/transportProperties:14:17: expected a positive kinematic viscosity"
            in rejected.stderr)
    assert "point-0001 (nu=0.1, deltaT=0.5): fsimFoam: error: deltaT = 5e-1 s exceeds the " \
        "stability bound" in rejected.stderr
    assert "point-0000 (" not in rejected.stderr
    points = sorted(out.glob("point-*"))
    assert len(points) == 4 and not any(ran(p) for p in points)


def test_a_failed_point_is_in_the_table_and_the_others_finish(fsim, tmp_path):
    """Poiseuille flow at a fixed step: deltaT 0.045 s passes the dry run but fails at step 16
    once the profile's centre speeds up; 0.02 and 0.03 s finish at the exact gradient 12 nu
    U / H^2 less the grid's 0.78 %."""
    out = tmp_path / "channel"
    args = ["run", "channel", "--set", "system/controlDict:adjustTimeStep=no",
            "--set", "system/fvOptions:momentumSource/Ubar=(0.02 0 0)",
            "--set", "system/controlDict:endTime=10",
            "--set", "system/controlDict:deltaT=0.045,0.02,0.03",
            "--out", out, "--fsim", fsim]
    done = run_study(args, timeout=300)
    assert done.returncode == 1, done.stderr
    rows = {r["deltaT"]: r for r in table(out)}
    failed = rows["0.045"]
    assert failed["status"] == "failed" and failed["exit_code"] == "1"
    assert failed["message"].startswith("fsimFoam: error: deltaT = 4.5e-2 s exceeds the "
                                        "stability bound")
    assert "(step 16;" in failed["message"]
    record = json.loads((out / failed["point"] / "done.json").read_text())
    assert record["stderr_tail"] and "exceeds the stability bound" in record["message"]
    for dt in ("0.02", "0.03"):
        r = rows[dt]
        assert r["status"] == "done" and r["exit_code"] == "0"
        assert float(r["reference.drivingGradient"]) == pytest.approx(12e-6 * 0.02 / 0.01 ** 2)
        assert float(r["error.fluid.drivingGradient.final"]) == pytest.approx(0.0075, abs=5e-4)
    # A failed point is final too: the same command runs nothing.
    again = run_study(args, timeout=120)
    assert again.returncode == 1
    assert "3 finished before, 0 to run" in again.stderr
