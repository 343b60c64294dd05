# Sourced by the check scripts: `check NAME COMMAND...` runs a command as one test case (its
# output goes to $CHECK_LOG_DIR/NAME.log, shown on failure) and `finish_checks SUITE` prints
# "N passed, M failed", writes a JUnit report to $JUNIT_DIR/SUITE.xml when JUNIT_DIR is set
# (make test counts it), and returns non-zero on a failure.
CHECK_LOG_DIR="${CHECK_LOG_DIR:-$(mktemp -d)}"
check_passed=0
check_failed=0
check_cases=""
check() {
  local name=$1
  shift
  local log="$CHECK_LOG_DIR/$name.log"
  if "$@" >"$log" 2>&1; then
    echo "[$CHECK_SUITE] $name: ok"
    check_passed=$((check_passed + 1))
    check_cases+="<testcase classname=\"$CHECK_SUITE\" name=\"$name\"/>"
  else
    echo "[$CHECK_SUITE] $name: FAILED (log: $log)"
    tail -30 "$log"
    check_failed=$((check_failed + 1))
    local text
    # Control characters (terminal colours) are not allowed in XML: dropped, tabs and newlines kept.
    text=$(tail -30 "$log" | tr -d '\000-\010\013\014\016-\037' |
           sed -e 's/&/\&amp;/g' -e 's/</\&lt;/g' -e 's/>/\&gt;/g' -e 's/"/\&quot;/g')
    check_cases+="<testcase classname=\"$CHECK_SUITE\" name=\"$name\"><failure message=\"$text\"/></testcase>"
  fi
}
finish_checks() {
  if [[ -n "${JUNIT_DIR:-}" ]]; then
    mkdir -p "$JUNIT_DIR"
    printf '<?xml version="1.0" encoding="UTF-8"?>\n<testsuite name="%s" tests="%d" failures="%d">%s</testsuite>\n' \
      "$CHECK_SUITE" $((check_passed + check_failed)) "$check_failed" "$check_cases" >"$JUNIT_DIR/$CHECK_SUITE.xml"
  fi
  echo "$check_passed passed, $check_failed failed"
  [[ $check_failed -eq 0 ]]
}
