#!/usr/bin/env bash
# make test-readme: every shell command block of README.md and docs/*.md run as a new user would
# (see scripts/readme_check.py); then the generated tables: docs/performance.md's figures equal
# what scripts/readme_figures.py writes from bench/results/*.json, docs/parameters.md's what
# scripts/param_docs.py writes from the parameter tables (which also checks the launch files).
set -uo pipefail
source "$(dirname "$0")/env.sh"
exec python3 "$ROOT/scripts/readme_check.py" "$@"
