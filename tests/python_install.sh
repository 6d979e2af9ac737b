#!/usr/bin/env bash
# `pip install .` as a Python user does it, offline: a fresh virtual
# environment of Debian's python3 that sees the system's packages (numpy,
# pytest, setuptools, pybind11), the module built from a copy of this clone
# by pyproject.toml's backend, then the Python tests against the installed
# module from outside the source tree. Also `pip wheel .`. Usage:
#   bash tests/python_install.sh [HGRID_BINARY]    (default build/hgrid; the tests compare with it)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
hgrid=$(realpath "${1:-$root/build/hgrid}")
py=${PYTHON:-/usr/bin/python3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# A copy without build folders: what a fresh clone holds.
mkdir -p "$work/src" && (cd "$root" && git ls-files -z --cached --others --exclude-standard | xargs -0 cp --parents -t "$work/src")
"$py" -m venv --system-site-packages "$work/v"
"$work/v/bin/pip" --version
"$work/v/bin/pip" install --no-index --no-build-isolation "$work/src"
"$work/v/bin/pip" wheel --no-index --no-build-isolation --no-deps -w "$work/wheels" "$work/src" >/dev/null
ls "$work"/wheels/hgridlab-*.whl
cd "$work"
where=$("$work/v/bin/python" -c "import hgridlab; print(hgridlab.__file__)")
case "$where" in "$work/v/"*) echo "hgridlab imported from $where" ;; *) echo "error: hgridlab imported from $where, not the venv" >&2; exit 1 ;; esac
HGRID_BINARY="$hgrid" "$work/v/bin/python" -m pytest -q -p no:cacheprovider "$root/python/tests"
