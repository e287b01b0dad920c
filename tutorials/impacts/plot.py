#!/usr/bin/env python3
"""Bead-bead and bead-wall impacts with Hertzian contacts, alpha 0.1: restitution (about 0.87),
tangential velocity and spin after each impact, against the contact's equation, Coulomb's
bound and rolling. Prints each quantity and draws impacts.png (plotting.impacts, which
impactsDamped's plot.py runs too).
"""
import sys
from pathlib import Path

case = Path(__file__).resolve().parent
sys.path.insert(0, str(case.parent))  # tutorials/, for plotting.py
from plotting import impacts  # noqa: E402

impacts(case)
