#!/usr/bin/env bash
# Creates .venv at the repository root with the pinned Python tools of tools/requirements.txt.
# Idempotent: when .venv already holds exactly this requirements file, it returns at once.
# Usage: tools/setup_venv.sh   (then use .venv/bin/python, .venv/bin/pytest)
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$repo_root/.venv"
requirements="$repo_root/tools/requirements.txt"
stamp="$venv/.fsim-requirements.sha256"

python="${PYTHON:-}"
if [ -z "$python" ]; then
    for candidate in python3.11 python3; do
        if command -v "$candidate" >/dev/null 2>&1; then
            python="$candidate"
            break
        fi
    done
fi
if [ -z "$python" ]; then
    echo "setup_venv.sh: no python3 found (CPython 3.11 is the tested version)" >&2
    exit 1
fi

wanted="$(sha256sum "$requirements" | cut -d' ' -f1)"
if [ -x "$venv/bin/python" ] && [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$wanted" ]; then
    exit 0
fi

if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$requirements"
echo "$wanted" > "$stamp"
echo "setup_venv.sh: Python tools installed in $venv"
