#!/usr/bin/env bash
# Debian packages the checks use when they are there: OpenFOAM's examples (the parser reads
# every dictionary of its tutorials; DPMFoam runs live in the cross-check, DPMFoam and icoFoam
# in the benchmarks) and ParaView's pvpython (opens fsim's collection file as a ParaView user would).
# Installs only what is missing; without root or apt it says so and the checks that need the
# packages report themselves skipped.
set -euo pipefail
need=()
{ [ -d /usr/share/doc/openfoam-examples/examples ] && command -v DPMFoam >/dev/null 2>&1; } \
    || need+=(openfoam openfoam-examples)
command -v pvpython >/dev/null 2>&1 || need+=(python3-paraview)
if [ ${#need[@]} -eq 0 ]; then
    exit 0
fi
if [ "$(id -u)" -ne 0 ] || ! command -v apt-get >/dev/null 2>&1; then
    echo "note: cannot install ${need[*]} (needs root and apt-get); their checks will be skipped"
    exit 0
fi
echo "== installing ${need[*]}"
apt-get update -qq
DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
