# What the bash tests of tests/cli and tests/mpi share. Each script runs one case, a function
# case_NAME, in an empty scratch directory, and fails with the reason on stderr:
#
#   source "$(dirname "${BASH_SOURCE[0]}")/../support/bash_case.bash"
#   case_name=$1 ...
#   enter_scratch "$scratch"
#   case_NAME() { ...; fail "why"; }
#   run_case "$case_name" [ARG...]

# Fails the case: the reason, then the stderr of the last run if it left one (err.log).
fail() {
  echo "FAIL ($case_name): $*" >&2
  [[ -f err.log ]] && { echo "--- stderr of the last run:" >&2; cat err.log >&2; }
  exit 1
}

# Makes DIR empty and works in it.
enter_scratch() { # DIR
  rm -rf "$1" && mkdir -p "$1" && cd "$1" || exit 1
}

# Runs case_NAME with the arguments; status 2 for a name that is no case.
run_case() { # NAME [ARG...]
  local name=$1
  shift
  declare -F "case_$name" >/dev/null || { echo "no case '$name'" >&2; exit 2; }
  "case_$name" "$@"
}
