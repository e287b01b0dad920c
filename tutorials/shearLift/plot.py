#!/usr/bin/env python3
"""One bead settling in a vertical linear shear flow with SaffmanMeiLiftForce (shearLift) or
TomiyamaLift (shearLiftTomiyama), a DPMFoam cross-check case of issue 42.

The water moves along z at u_z = gamma (x - width/2) between two walls sliding in opposite
directions; the bead settles through it with the slip s_z and the lift
m rho_f/rho_p Cl (s x curl u) drives it across the stream lines at the speed where drag
balances it (tools/force_crosscheck_references.py shearLift solves that balance: Saffman 1965
and Mei 1992, or Tomiyama's C_l, as DPMFoam v1912 writes them). Draws <case>.png: the
bead's x and U_x, fsim's and DPMFoam's (crosscheck_reference.csv), against that drift.
"""
import sys
from pathlib import Path

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import shear_lift  # noqa: E402

shear_lift(case)
