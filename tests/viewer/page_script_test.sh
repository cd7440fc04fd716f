#!/bin/sh
# glint-compare's page script, which no build compiles, parsed by Node.js (node --check: syntax
# only) before a browser meets it:
#
#   page_script_test.sh SCRIPT
#
# Exit status 0 when it parses, 1 when it does not (node names the line), 77 when node is not
# installed (ctest's SKIP_RETURN_CODE: reported as skipped, with the reason on stderr).
set -eu
script=$1
if ! command -v node >/dev/null 2>&1; then
  echo "SKIPPED: node is not installed (Debian: nodejs), so $script was not parsed" >&2
  exit 77
fi
node --check "$script"
echo "PASS: $script parses"
