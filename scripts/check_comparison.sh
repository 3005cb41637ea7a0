#!/usr/bin/env bash
# CI job: the summary check of the committed comparison sets (scripts/check_results.sh
# --comparison: a short replay of arch-flat, arch-curved, block and the FCLIB problem set against
# the committed records, by scripts/diff_comparison.py; about two minutes).
set -euo pipefail
exec bash "$(dirname "${BASH_SOURCE[0]}")/check_results.sh" --comparison "$@"
