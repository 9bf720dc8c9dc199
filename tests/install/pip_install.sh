#!/usr/bin/env bash
# `pip install .` as the README says it, into a fresh virtual environment of Debian's Python, then
# the package imported and used from another folder: the installed copy, not the source tree's.
# Usage: pip_install.sh SOURCE_DIR WORK_DIR PYTHON
set -euo pipefail
source_dir="$1"
work="$2"
python="$3"

rm -rf "$work"
mkdir -p "$work/elsewhere"
"$python" -m venv --system-site-packages "$work/venv"
"$work/venv/bin/pip" install --no-build-isolation --no-index --quiet "$source_dir"

cd "$work/elsewhere"
expected="$(sed -n 's/^#define SPHYS_VERSION_\(MAJOR\|MINOR\|PATCH\) \([0-9]*\)$/\2/p' \
  "$source_dir/include/sphys/version.h" | paste -sd.)"
"$work/venv/bin/python" - "$work/venv" "$expected" <<'PYTHON'
import sys

import sphys

venv, expected = sys.argv[1:]
assert sphys.__file__.startswith(venv), f"sphys imported from {sphys.__file__}, not {venv}"
assert sphys.__version__ == expected, f"sphys.__version__ {sphys.__version__}, header {expected}"
# A cube of side 2 m at 1000 kg/m^3 weighs 8000 kg.
mass = sphys.mass_properties(sphys.box((2.0, 2.0, 2.0)), density=1000.0).mass
assert abs(mass - 8000.0) < 1e-9, mass
print(f"sphys {sphys.__version__} installed by pip into {venv}")
PYTHON
# An example, run from here by the virtual environment's Python with nothing else on its path.
"$work/venv/bin/python" "$source_dir/examples/python/check_configurations.py"
