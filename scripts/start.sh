#!/usr/bin/env bash
# Install jackpy and its system packages, then open the workbench (default human, default scene).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-system-deps.sh
python3 -m pip install -q --disable-pip-version-check -e '.[cad,planning,fast]'
exec jackpy "$@"
