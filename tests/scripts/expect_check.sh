# Sourced by the tests of the repository checks (check-layers-test.sh, check-docs-test.sh): one
# way to run a check on the copy of the tree in "$tmp/tree" and count the outcome.
passed=0
failed=0
# expect_check CHECK RC PATTERN NAME: the check script CHECK on the copy exits RC and its output
# matches PATTERN.
expect_check() {
  local check=$1 rc=$2 pattern=$3 name=$4 out got
  out=$(bash "$check" "$tmp/tree" 2>&1)
  got=$?
  if [ "$got" = "$rc" ] && grep -qE -- "$pattern" <<<"$out"; then
    passed=$((passed + 1))
    echo "ok: $name"
  else
    failed=$((failed + 1))
    echo "FAIL: $name (exit $got, wanted $rc and /$pattern/):"
    echo "$out"
  fi
}
# Prints "N passed, M failed"; fails when a case did.
finish_checks() {
  echo "$passed passed, $failed failed"
  [ "$failed" = 0 ]
}
