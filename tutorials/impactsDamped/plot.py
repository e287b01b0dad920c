#!/usr/bin/env python3
"""The impacts of tutorials/impacts damped five times harder, alpha 0.5: restitution about 0.49,
and the tangential dashpot stops the slip before Coulomb's bound binds (the beads leave
rolling). plotting.impacts, as for impacts, prints each quantity and draws impactsDamped.png.
"""
import sys
from pathlib import Path

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import impacts  # noqa: E402

impacts(case)
