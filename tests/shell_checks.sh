# Sourced by the shell tests: a scratch folder removed at exit, pass/fail counting, and the
# one-line-error check. The including script sets `set -u` and calls `finish` at its end.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passes=0 failures=0
check() {  # check DESCRIPTION COMMAND...
  local what=$1; shift
  if "$@"; then echo "ok: $what"; passes=$((passes + 1)); else echo "FAILED: $what"; failures=$((failures + 1)); fi
}
fails_clearly() {  # fails_clearly EXPECTED_TEXT COMMAND...: non-zero exit, one stderr line with the text
  local expected=$1; shift
  "$@" >"$work/out" 2>"$work/err" && return 1
  [ "$(wc -l <"$work/err")" -eq 1 ] && grep -qF -- "$expected" "$work/err" || { cat "$work/err" >&2; return 1; }
}
finish() {
  echo "$passes passed, $failures failed"
  exit $((failures != 0))
}
