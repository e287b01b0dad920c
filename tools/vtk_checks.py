"""Checks of the files fsim writes in a case directory, with meshio, pyvista and ParaView.

Each check takes a case directory, raises AssertionError with a message naming the file on
the first problem, and returns what it read so callers can compare values with what they
expect (see tests/test_vtk_output.py for a sample run with analytic fields).

    python tools/vtk_checks.py CASE_DIR      # all checks, one line per file, exit 1 on failure

What is checked:
- the collection file <case>/<caseName>.pvd lists every time directory's fluid.vti and
  particles.vtu in time order, and pyvista's reader reports the same times;
- every fluid.vtk is read by meshio and pyvista, every fluid.vti by pyvista, and all three give
  the same cell centres and the same arrays bit for bit;
- every particles.vtu is read by pyvista and (when it has particles) by meshio, identically;
  meshio 5.3.5 reads no unstructured file with zero cells, not even one it wrote itself;
- every restart.bin decodes (documented layout, CRC-32) and its time rounds to its directory's name;
- ParaView (pvpython, when installed) opens the collection, sees the same times, and reads
  the same values as meshio.
"""

from __future__ import annotations

import json
import os
import shutil
import struct
import subprocess
import sys
import warnings
import xml.etree.ElementTree as ElementTree
import zlib
from pathlib import Path

import numpy as np

FLUID_VTK = "fluid.vtk"
FLUID_VTI = "fluid.vti"
PARTICLES = "particles.vtu"
RESTART = "restart.bin"
TOOLS_DIR = Path(__file__).resolve().parent


def time_directories(case: Path) -> list[tuple[str, float]]:
    """Numeric directories of the case, sorted by time (hidden partial ones excluded)."""
    times = []
    for entry in Path(case).iterdir():
        name = entry.name
        if not entry.is_dir() or not (name[0].isdigit() or name[0] in "+-"):
            continue
        try:
            value = float(name)
        except ValueError:
            continue
        if np.isfinite(value):
            times.append((name, value))
    return sorted(times, key=lambda t: t[1])


def collection_path(case: Path) -> Path:
    case = Path(case)
    return case / f"{case.resolve().name}.pvd"


def read_collection(case: Path) -> list[dict]:
    """The <DataSet> entries of the collection file, in file order."""
    path = collection_path(case)
    assert path.is_file(), f"{path}: collection file missing"
    root = ElementTree.parse(path).getroot()
    assert root.get("type") == "Collection", f"{path}: not a VTK collection"
    return [
        {"time": float(d.get("timestep")), "part": int(d.get("part", 0)), "file": d.get("file")}
        for d in root.iter("DataSet")
    ]


def check_collection(case: Path) -> list[float]:
    """The collection lists exactly the fluid and particle files of the time directories, in
    time order, and pyvista reads the same time values. Returns those times."""
    import pyvista

    case = Path(case)
    path = collection_path(case)
    entries = read_collection(case)
    times = [e["time"] for e in entries]
    assert times == sorted(times), f"{path}: times out of order: {times}"
    for e in entries:
        assert (case / e["file"]).is_file(), f"{path}: lists missing file {e['file']}"
    expected = []
    for name, value in time_directories(case):
        for part, file in enumerate([FLUID_VTI, PARTICLES]):
            if (case / name / file).is_file():
                expected.append((value, part, f"{name}/{file}"))
    listed = [(e["time"], e["part"], e["file"]) for e in entries]
    assert listed == expected, f"{path}: lists {listed}, time directories hold {expected}"
    unique = sorted(set(times))
    reader = pyvista.get_reader(str(path))
    assert list(reader.time_values) == unique, (
        f"{path}: pyvista sees times {reader.time_values}, expected {unique}"
    )
    return unique


def _meshio_read(path: Path):
    import meshio

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return meshio.read(str(path))


def read_fluid(case: Path, time_name: str) -> dict:
    """Cell centres and cell arrays of one time, read by meshio from fluid.vtk, after checking
    that pyvista reads fluid.vtk and fluid.vti to the same values."""
    import pyvista

    directory = Path(case) / time_name
    legacy = directory / FLUID_VTK
    mesh = _meshio_read(legacy)
    assert len(mesh.cells) == 1 and mesh.cells[0].type == "hexahedron", (
        f"{legacy}: meshio sees cells {[c.type for c in mesh.cells]}"
    )
    centres = mesh.points[mesh.cells[0].data].mean(axis=1)
    arrays = {}
    for name, blocks in mesh.cell_data.items():
        values = np.asarray(blocks[0])
        if values.ndim == 2 and values.shape[1] == 1:  # meshio keeps SCALARS as (n, 1)
            values = values[:, 0]
        arrays[name] = values
    for path in [legacy, directory / FLUID_VTI]:
        if not path.is_file():
            assert path.name != FLUID_VTK, f"{path}: missing"
            continue
        grid = pyvista.read(str(path))
        assert grid.n_cells == len(centres), f"{path}: {grid.n_cells} cells, meshio saw {len(centres)}"
        assert np.allclose(grid.cell_centers().points, centres, rtol=0, atol=1e-12 * _scale(centres)), (
            f"{path}: pyvista's cell centres differ from meshio's"
        )
        assert set(grid.cell_data.keys()) == set(arrays), (
            f"{path}: arrays {list(grid.cell_data.keys())}, meshio saw {list(arrays)}"
        )
        for name, values in arrays.items():
            assert np.array_equal(np.asarray(grid.cell_data[name]), values), (
                f"{path}: array {name} differs between pyvista and meshio"
            )
    return {"centres": centres, **arrays}


def _scale(points: np.ndarray) -> float:
    return max(1.0, float(np.abs(points).max())) if points.size else 1.0


def check_fluid(case: Path) -> dict[str, dict]:
    """read_fluid for every time directory that holds fluid output."""
    return {
        name: read_fluid(case, name)
        for name, _ in time_directories(case)
        if (Path(case) / name / FLUID_VTK).is_file() or (Path(case) / name / FLUID_VTI).is_file()
    }


def read_particles(case: Path, time_name: str) -> dict:
    """Positions and point arrays of one time's particles.vtu, read by pyvista and compared
    with meshio's reading when the file holds particles."""
    import pyvista

    path = Path(case) / time_name / PARTICLES
    grid = pyvista.read(str(path))
    assert grid.n_cells == grid.n_points, f"{path}: {grid.n_cells} cells for {grid.n_points} points"
    if grid.n_cells:
        assert set(np.unique(grid.celltypes)) == {pyvista.CellType.VERTEX}, f"{path}: not VERTEX cells"
    data = {"positions": np.asarray(grid.points).reshape(-1, 3)}
    for name in grid.point_data.keys():
        data[name] = np.asarray(grid.point_data[name])
    if grid.n_points:
        mesh = _meshio_read(path)
        assert np.array_equal(mesh.points, data["positions"]), f"{path}: meshio positions differ"
        for name, values in mesh.point_data.items():
            assert np.array_equal(np.asarray(values), data[name]), f"{path}: meshio `{name}` differs"
        assert set(mesh.point_data) == set(data) - {"positions"}, f"{path}: array names differ"
    return data


def check_particles(case: Path) -> dict[str, dict]:
    """read_particles for every time directory that holds particles."""
    return {
        name: read_particles(case, name)
        for name, _ in time_directories(case)
        if (Path(case) / name / PARTICLES).is_file()
    }


def read_restart(path: Path) -> tuple[dict, dict[str, np.ndarray]]:
    """Decodes restart.bin by its documented layout (src/output/restart_state.rs): magic
    FSIMSTAT, u32 version 1, u64 payload length, payload, CRC-32 of everything before it."""
    path = Path(path)
    raw = path.read_bytes()
    assert raw[:8] == b"FSIMSTAT", f"{path}: bad magic"
    version, payload = struct.unpack_from("<IQ", raw, 8)
    assert version == 1, f"{path}: format version {version}"
    assert len(raw) == 20 + payload + 4, f"{path}: truncated ({len(raw)} bytes, header says {24 + payload})"
    (stored,) = struct.unpack_from("<I", raw, len(raw) - 4)
    assert zlib.crc32(raw[:-4]) == stored, f"{path}: checksum mismatch"
    at = 20
    time, step, delta_t = struct.unpack_from("<dQd", raw, at)
    at += 24

    def string():
        nonlocal at
        (n,) = struct.unpack_from("<I", raw, at)
        at += 4 + n
        return raw[at - n : at].decode()

    (n_meta,) = struct.unpack_from("<I", raw, at)
    at += 4
    metadata = {}
    for _ in range(n_meta):
        key = string()
        metadata[key] = string()
    (n_arrays,) = struct.unpack_from("<I", raw, at)
    at += 4
    arrays = {}
    for _ in range(n_arrays):
        name = string()
        (count,) = struct.unpack_from("<Q", raw, at)
        at += 8
        arrays[name] = np.frombuffer(raw, dtype="<f8", count=count, offset=at)
        at += 8 * count
    assert at == len(raw) - 4, f"{path}: {len(raw) - 4 - at} bytes left after the payload"
    header = {"time": time, "step": step, "delta_t": delta_t, "metadata": metadata}
    return header, arrays


def check_restart(case: Path) -> dict[str, tuple[dict, dict]]:
    """Every restart.bin decodes, and its time rounds to its directory's name."""
    out = {}
    for name, value in time_directories(case):
        path = Path(case) / name / RESTART
        if not path.is_file():
            continue
        header, arrays = read_restart(path)
        # The name is the time in C's %g at the case's timePrecision, whatever that was.
        assert any(float(f"%.{p}g" % header["time"]) == value for p in range(1, 18)), (
            f"{path}: time {header['time']} does not round to directory name {name}"
        )
        out[name] = (header, arrays)
    return out


def read_monitor(path: Path) -> tuple[list[str], np.ndarray]:
    """Column names (from the `# ` header) and rows of a postProcessing .dat file."""
    path = Path(path)
    with open(path) as f:
        header = f.readline()
    assert header.startswith("# "), f"{path}: first line is not a `# ` header"
    columns = header[2:].split()
    rows = np.loadtxt(path, comments="#", ndmin=2)
    assert rows.shape[1] == len(columns) or rows.size == 0, f"{path}: rows do not match {columns}"
    return columns, rows


def pvpython() -> str | None:
    return shutil.which("pvpython")


def check_paraview(case: Path, fluid: dict[str, dict] | None = None) -> dict | None:
    """ParaView opens the collection, sees the collection's times, and reads (when `fluid` is
    given) the first, middle and last value of every fluid array as meshio did. None when
    pvpython is not installed."""
    exe = pvpython()
    if exe is None:
        return None
    path = collection_path(case)
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    run = subprocess.run(
        [exe, str(TOOLS_DIR / "pv_read_collection.py"), str(path)],
        capture_output=True, text=True, timeout=600, env=env,
    )
    lines = [l for l in run.stdout.splitlines() if l.startswith("FSIM-JSON ")]
    assert run.returncode == 0 and lines, (
        f"{path}: ParaView failed (exit {run.returncode}): {run.stderr[-2000:]}"
    )
    seen = json.loads(lines[-1][len("FSIM-JSON "):])
    times = sorted({e["time"] for e in read_collection(case)})
    assert seen["times"] == times, f"{path}: ParaView sees times {seen['times']}, expected {times}"
    if fluid is not None:
        by_time = {value: name for name, value in time_directories(case)}
        for step in seen["steps"]:
            name = by_time[step["time"]]
            images = [b for b in step["blocks"] if b["class"] == "vtkImageData"]
            if name not in fluid:
                continue
            assert len(images) == 1, f"{path}: time {name}: ParaView sees {len(images)} fluid blocks"
            for array, values in images[0]["cell_arrays"].items():
                ours = np.asarray(fluid[name][array])
                ours = ours[:, 0] if ours.ndim == 2 else ours
                picks = [ours[0], ours[len(ours) // 2], ours[-1]]
                assert values == [float(v) for v in picks], (
                    f"{path}: time {name}: ParaView reads {array} = {values}, meshio {picks}"
                )
    return seen


def check_case(case: Path, log=print) -> dict:
    """All checks on one case directory."""
    case = Path(case)
    times = check_collection(case)
    log(f"{collection_path(case)}: {len(times)} times, pyvista agrees")
    fluid = check_fluid(case)
    for name, f in fluid.items():
        log(f"{case / name / FLUID_VTK}: meshio and pyvista (.vtk, .vti) agree: "
            f"{len(f['centres'])} cells, arrays {sorted(k for k in f if k != 'centres')}")
    particles = check_particles(case)
    for name, p in particles.items():
        log(f"{case / name / PARTICLES}: {len(p['positions'])} particles, readers agree")
    restart = check_restart(case)
    log(f"restart files: {len(restart)} decode with valid checksums")
    paraview = check_paraview(case, fluid)
    log("ParaView: not installed, skipped" if paraview is None
        else f"ParaView opens {collection_path(case).name}: times {paraview['times']}")
    return {"times": times, "fluid": fluid, "particles": particles, "restart": restart,
            "paraview": paraview}


def main(argv: list[str]) -> int:
    if len(argv) != 2:
        print(__doc__)
        return 2
    try:
        check_case(Path(argv[1]))
    except AssertionError as error:
        print(f"FAILED: {error}", file=sys.stderr)
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
