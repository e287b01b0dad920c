"""Writing OpenFOAM-format case files: the FoamFile header every tutorial generator shares
(tools/direct_cases.py and, through tools/dpmfoam_case.py's dictionaries, the DPMFoam cases'
generators tools/make_*.py)."""
import os

HEADER = """/*--------------------------------*- C++ -*----------------------------------*\\
  fsim: particles in a fluid at the particle scale
\\*---------------------------------------------------------------------------*/
FoamFile
{{
    version     2.0;
    format      ascii;
    class       {cls};
    location    "{loc}";
    object      {obj};
}}
"""


def write(root, rel, cls, body, gap=""):
    """Writes `root/rel` (directories made as needed): the header for class `cls`, then
    `gap`, then `body` without its leading newlines."""
    path = os.path.join(root, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    loc, obj = os.path.split(rel)
    with open(path, "w") as f:
        f.write(HEADER.format(cls=cls, loc=loc, obj=obj) + gap + body.lstrip("\n"))
