#!/usr/bin/env bash
# CI job: formatting and lint. Every tracked C++ file (.h, .cc) must be what clang-format makes
# of it with .clang-format (Debian's clang-format; the layout depends on its version, bookworm's
# is 14), and the Python (results/, tests/python/, scripts/*.py) must pass flake8 with .flake8.
# Prints each offending file (a C++ file: how to mend it; a Python file: flake8's findings); any
# finding fails the job.
# Usage: scripts/check_format.sh
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"

"$here/scripts/install_packages.sh" format  # scripts/packages.txt

tracked() { git ls-files "$@" 2>/dev/null; }
mapfile -t cxx < <(tracked '*.h' '*.cc' ||
  find src formulations bench fuzz tests -name '*.h' -o -name '*.cc')
mapfile -t python < <(tracked 'results/*.py' 'tests/python/*.py' 'scripts/*.py' 'python/*.py' \
  'tests/python_module/*.py' ||
  find results tests/python scripts -name '*.py')

status=0
echo "check_format: $(clang-format --version) on ${#cxx[@]} C++ files" >&2
unformatted=0
for file in "${cxx[@]}"; do
  if ! clang-format --dry-run --Werror "$file" >/dev/null 2>&1; then
    echo "check_format: $file is not formatted (clang-format -i $file)" >&2
    unformatted=$((unformatted + 1))
  fi
done
if ((unformatted)); then
  echo "check_format: clang-format FAILED: $unformatted of ${#cxx[@]} C++ files" >&2
  status=1
fi

flake8_version="$(flake8 --version | head -n 1 | cut -d' ' -f1)"
echo "check_format: flake8 $flake8_version on ${#python[@]} Python files" >&2
if ! flake8 --config "$here/.flake8" "${python[@]}" >&2; then
  echo "check_format: flake8 FAILED" >&2
  status=1
fi

((status == 0)) && echo "check_format: clean" >&2
exit $status
