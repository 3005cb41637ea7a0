#!/usr/bin/env bash
# CI job: static analysis of the sources. clang-tidy with the checks of .clang-tidy (each with
# its reason) on every translation unit of the library, the formulations, the harness, the
# driver and the fuzz targets (from BUILD_DIR/compile_commands.json); cppcheck with
# warning, performance and portability checks. Any finding fails the job. A finding that is
# not a defect is suppressed where it stands (// NOLINT(check): reason, or
# // cppcheck-suppress id with the reason), never here, except the global cppcheck
# suppressions below, each with its reason.
# Usage: scripts/check_static.sh [BUILD_DIR]   (default build-tidy)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build-tidy}"

"$here/scripts/install_packages.sh" static  # scripts/packages.txt

# Configuring gives compile_commands.json; the one generated header (the build info that
# run.json records) is made by its own target, without compiling anything. PETSc and Siconos
# are analysed as their stubs, installed or not (docs/hardening.md).
cmake -S "$here" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
  -DCONTACTBENCH_FUZZ=ON -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
  -DCONTACTBENCH_WITH_PETSC=OFF -DCONTACTBENCH_WITH_SICONOS=OFF >/dev/null
cmake --build "$build" --target contactbench_build_info >/dev/null

# The sources we analyse: everything but the tests (GoogleTest's macros trip bugprone checks by
# the hundred, and the tests run under the sanitizers instead).
mapfile -t sources < <(cd "$here" && git ls-files 'src/*.cc' 'formulations/*.cc' 'bench/*.cc' \
  'fuzz/*.cc' 2>/dev/null || find src formulations bench fuzz -name '*.cc')
echo "check_static: clang-tidy on ${#sources[@]} files" >&2
status=0
run-clang-tidy -quiet -p "$build" -j "$(nproc)" "${sources[@]/#/$here/}" \
  > "$build/clang-tidy.log" 2>&1 || status=1
if ((status)); then
  grep -E "(warning|error):" "$build/clang-tidy.log" | sort -u >&2 || tail -n 50 "$build/clang-tidy.log" >&2
  echo "check_static: clang-tidy FAILED (log: $build/clang-tidy.log)" >&2
fi

# cppcheck on the same sources, without the system headers (missingIncludeSystem): it checks
# our code, not Eigen's. Global suppressions:
#  - missingIncludeSystem: system and dependency headers are deliberately not given.
#  - unmatchedSuppression: an inline suppression may match in one configuration only.
#  - useInitializationList: a member assigned in the constructor body instead of the
#    initialiser list; for the unique_ptr and small members it flags the cost is nil, and
#    bench/harness/records.cc builds each CSV writer there with its long column list on purpose.
echo "check_static: cppcheck" >&2
if ! cppcheck --quiet --enable=warning,performance,portability --error-exitcode=1 \
    --std=c++20 --language=c++ --inline-suppr -j "$(nproc)" \
    --suppress=missingIncludeSystem --suppress=unmatchedSuppression \
    --suppress=useInitializationList \
    -I "$here/src" -I "$here" -I "$here/bench" \
    -DCONTACTBENCH_HAVE_SUITESPARSE=1 \
    --template='{file}:{line}: {severity} ({id}): {message}' \
    "${sources[@]/#/$here/}" 2> "$build/cppcheck.log"; then
  status=1
  cat "$build/cppcheck.log" >&2
  echo "check_static: cppcheck FAILED" >&2
fi
((status == 0)) && echo "check_static: clean" >&2
exit $status
