import sys
from pathlib import Path

# The checks live in tools/vtk_checks.py; make them importable from the tests.
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
