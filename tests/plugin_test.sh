#!/usr/bin/env bash
# ctest's cli.plugin: `--plugin FILE` (bench/harness/plugins.h) with examples/plugin's
# min-newton: listed, compared beside a built-in formulation and verified by the verdict, rerun;
# refused with exit status 2 and the reason when loaded twice, missing, or without the entry
# point.
# Usage: tests/plugin_test.sh CONTACTBENCH LIBMIN_NEWTON
set -euo pipefail
driver="$1"
plugin="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail() {
  echo "plugin_test: $1" >&2
  cat "$tmp/err" >&2 || true
  exit 1
}

"$driver" list --plugin "$plugin" >"$tmp/list" 2>"$tmp/err" || fail "list --plugin failed"
grep -q "min-newton" "$tmp/list" || fail "list does not show min-newton"

"$driver" compare --plugin "$plugin" --problem arch-flat --formulations min-newton,active-set \
  --starts warm --steps 4 --out "$tmp/cmp" 2>"$tmp/err" || fail "compare --plugin failed"
grep -q "^arch-flat,min-newton,eigen-sparselu,.*,converged," "$tmp/cmp/runs.csv" ||
  fail "min-newton did not verify every step: $(cat "$tmp/cmp/runs.csv")"

"$driver" rerun "$tmp/cmp" --out "$tmp/again" 2>"$tmp/err" || fail "rerun of a --plugin compare failed"
cmp -s <(cut -d, -f1-5 "$tmp/cmp/runs.csv") <(cut -d, -f1-5 "$tmp/again/runs.csv") ||
  fail "the rerun's runs.csv differs"

refused() {  # refused REASON ARGS...: exit status 2 and REASON on standard error
  local reason="$1"
  shift
  local status=0
  "$driver" compare --problem arch-flat --steps 1 --out "$tmp/no" "$@" 2>"$tmp/err" || status=$?
  ((status == 2)) || fail "$* exited with $status, not 2"
  grep -q "$reason" "$tmp/err" || fail "$* did not say '$reason'"
  [[ ! -e "$tmp/no" ]] || fail "$* wrote $tmp/no"
}
refused "already registered" --plugin "$plugin" --plugin "$plugin"
refused "cannot load" --plugin "$tmp/missing.so"
printf 'not a shared object\n' >"$tmp/text.so"
refused "cannot load" --plugin "$tmp/text.so"
libm="$(ldconfig -p | sed -n 's/.*libm.so.6 (libc6,x86-64) => //p' | head -n 1)"
if [[ -n $libm ]]; then
  refused "no entry point" --plugin "$libm"
fi
echo "plugin_test: ok"
