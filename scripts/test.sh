#!/usr/bin/env bash
# Install everything (system packages, jackpy with its test extras) and run the whole test suite.
# Window tests need an X display: without one, the suite runs under xvfb-run.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-system-deps.sh
python3 -m pip install -q --disable-pip-version-check -e '.[test,cad,planning,cluster,bench,fast]'
if [ -z "${DISPLAY:-}" ]; then
    exec xvfb-run -a -s "-screen 0 1600x1200x24" python3 -m pytest "$@"
fi
exec python3 -m pytest "$@"
