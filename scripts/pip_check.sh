#!/usr/bin/env bash
# The Python user's front door, as the README gives it: in a fresh virtual environment over
# Debian's packages (`python3 -m venv --system-site-packages`), `pip install
# --no-build-isolation .` from the repository root, with no package index (so no network),
# then the Python module's pytest suite (python/tests) against the installed package, run
# from outside the repository, without the workspace's PYTHONPATH.
# Writes JUnit XML to OUT/test_results: pytest's cases, or one failed case when the install
# fails (its log: OUT/pip.log). Exits non-zero when anything fails.
# Usage: scripts/pip_check.sh [OUT]   (default build/pip_check)
set -eo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=$(mkdir -p "${1:-$ROOT/build/pip_check}" && cd "${1:-$ROOT/build/pip_check}" && pwd)
VENV="$OUT/venv"
RESULTS="$OUT/test_results"
rm -rf "$VENV" "$RESULTS"
mkdir -p "$RESULTS"
# Debian's interpreter: its numpy, pybind11, setuptools and pytest are the ones the README's
# set-up installs (a pyenv python3 earlier in PATH has none of them).
/usr/bin/python3 -m venv --system-site-packages "$VENV"
if ! (cd "$ROOT" && env -u PYTHONPATH "$VENV/bin/pip" install --no-index --no-build-isolation .) \
    > "$OUT/pip.log" 2>&1; then
  echo '<?xml version="1.0"?><testsuite name="pip" tests="1" failures="1"><testcase classname="pip" name="install"><failure message="pip install --no-build-isolation . failed: see build/pip_check/pip.log"/></testcase></testsuite>' \
    > "$RESULTS/pip-install.xml"
  tail -n 20 "$OUT/pip.log" >&2
  echo "pip_check: pip install failed" >&2
  exit 1
fi
cd "$OUT"
env -u PYTHONPATH SAP_EXPECT_INSTALLED_IN="$VENV" \
  "$VENV/bin/python" "$ROOT/python/tests/run_tests.py" "$RESULTS/pytest-pip.xml"
