#!/usr/bin/env python3
"""Render a sedimentation run: the particles as spheres and a slice of the fluid velocity.

    tools/render_sedimentation.py [CASE] [--time T] [--out docs/sedimentation.png]

CASE defaults to tutorials/sedimentation; the time to the latest time directory. The slice is
the mid-plane normal to z, coloured by the vertical velocity U_y (m/s); the spheres are the
particles of `particles.vtu` at their diameters. Needs pyvista (tools/setup_venv.sh); renders
off screen.
"""
import argparse
import os
import re
import sys

import numpy as np
import pyvista as pv

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def time_dirs(case):
    out = []
    for name in os.listdir(case):
        if re.fullmatch(r"[0-9.eE+-]+", name) and os.path.isfile(os.path.join(case, name, "fluid.vti")):
            out.append((float(name), name))
    return sorted(out)


def render(case, time_name, out, size=(700, 1000), label=None):
    fluid = pv.read(os.path.join(case, time_name, "fluid.vti"))
    fluid = fluid.cell_data_to_point_data()
    bounds = fluid.bounds
    z_mid = 0.5 * (bounds[4] + bounds[5])
    plane = fluid.slice(normal="z", origin=(0.0, 0.0, z_mid))
    u = np.asarray(plane.point_data["U"])
    plane.point_data["U_y"] = u[:, 1]

    particles = pv.read(os.path.join(case, time_name, "particles.vtu"))
    d = np.asarray(particles.point_data["d"])
    cloud = pv.PolyData(np.asarray(particles.points))
    cloud.point_data["d"] = d
    spheres = cloud.glyph(geom=pv.Sphere(radius=0.5, theta_resolution=24, phi_resolution=24),
                          scale="d", orient=False)

    pv.OFF_SCREEN = True
    plotter = pv.Plotter(off_screen=True, window_size=size)
    plotter.set_background("white")
    lim = float(np.max(np.abs(u[:, 1]))) or 1.0
    plotter.add_mesh(plane, scalars="U_y", cmap="coolwarm", clim=(-lim, lim),
                     scalar_bar_args=dict(title="U_y (m/s)", color="black", vertical=True,
                                          fmt="%.2e", position_x=0.78, position_y=0.2, width=0.08))
    plotter.add_mesh(spheres, color="#d9a441", smooth_shading=True, specular=0.3)
    plotter.add_mesh(pv.Box(bounds).outline(), color="black")
    label = label or os.path.basename(os.path.abspath(case))
    plotter.add_text(f"{label}, t = {time_name} s, "
                     f"{len(d)} particles", font_size=12, color="black")
    # gravity along -y: y up, looking slightly down onto the mid-plane slice
    plotter.view_vector((0.55, 0.35, 1.0), viewup=(0.0, 1.0, 0.0))
    plotter.camera.zoom(1.25)
    plotter.screenshot(out)
    plotter.close()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case", nargs="?", default=os.path.join(ROOT, "tutorials", "sedimentation"))
    ap.add_argument("--time", help="time directory to render (default: the latest)")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "sedimentation.png"))
    ap.add_argument("--label", help="title of the picture (default: the case's folder name)")
    a = ap.parse_args()
    times = time_dirs(a.case)
    if not times:
        sys.exit(f"{a.case}: no time directory with fluid.vti; run fsimFoam -case {a.case} first")
    name = a.time if a.time else times[-1][1]
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    render(a.case, name, a.out, label=a.label)
    print(f"wrote {a.out} ({os.path.getsize(a.out) // 1024} kB) from {a.case}/{name}")


if __name__ == "__main__":
    main()
