#!/usr/bin/env bash
# make test-readme: every shell command block of the README run as a new user would (see
# scripts/readme_check.py); the README's tables of measured figures equal what
# scripts/readme_figures.py writes from bench/results/*.json.
set -uo pipefail
source "$(dirname "$0")/env.sh"
exec python3 "$ROOT/scripts/readme_check.py" "$@"
