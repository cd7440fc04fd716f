#!/usr/bin/env bash
# Checks a reference page against the program it documents, so that the two cannot drift apart.
#
#   reference_test.bash options DOC PROGRAM [BASE]
#       every option PROGRAM --help lists (less those BASE --help lists too) must appear in the
#       first cell of a table row of DOC, as `--option ...` or `-o ...`
#   reference_test.bash scene DOC KEYS_PROGRAM
#       KEYS_PROGRAM (tests/docs/scene_format_keys.cpp) prints the scene reader's statements,
#       keys and shading kinds from the reader's own tables. Every key of a statement must appear
#       in the first cell of a table row in the section of DOC whose heading starts with
#       `STATEMENT (subsections included); every shading kind in the first cell of a table row
#       under the heading "Shading kinds"; and the block after "<!-- complete example -->" must
#       be a valid scene that uses every statement and every key (its textures/ is
#       docs/images/textures).
set -euo pipefail

fail=0
missing() { # WHAT: reports one thing the page lacks
  echo "reference_test: $doc lacks $1" >&2
  fail=1
}

# The options a program's --help lists: on the lines that start with two spaces and a dash, the
# tokens starting with a dash before the description (which follows three or more spaces).
help_options() {
  "$@" --help | awk '/^  -/ {
      sub(/^ +/, ""); sub(/   .*$/, "")
      n = split($0, token, /[ ,]+/)
      for (i = 1; i <= n; i++) if (token[i] ~ /^--?[A-Za-z]/) print token[i]
    }' | sort -u
}

# The options in the first cells of DOC's table rows.
doc_options() {
  awk -F'|' '/^\|/ { print $2 }' "$1" | grep -oE '`--?[A-Za-z][A-Za-z-]*' | tr -d '`' | sort -u
}

case ${1:-} in
  options)
    doc=$2 program=$3 base=${4:-}
    [[ -f $doc ]] || { echo "reference_test: no $doc" >&2; exit 1; }
    help_options "$program" >options.txt
    [[ -s options.txt ]] || { echo "reference_test: $program --help lists no options" >&2; exit 1; }
    if [[ -n $base ]]; then
      help_options "$base" >base.txt
      comm -23 options.txt base.txt >own.txt
      mv own.txt options.txt
    fi
    doc_options "$doc" >documented.txt
    while read -r option; do
      grep -qxF -- "$option" documented.txt || missing "a table row for $option (from $program --help)"
    done <options.txt
    ((fail)) || echo "reference_test: $doc documents the $(wc -l <options.txt) options of $(basename "$program") --help"
    ;;
  scene)
    doc=$2 program=$3
    [[ -f $doc ]] || { echo "reference_test: no $doc" >&2; exit 1; }
    "$program" >accepted.txt
    # "STATEMENT KEY" for each key in a first cell of a row in the statement's section, and
    # "shading KIND" for the rows under "Shading kinds".
    awk '
      /^#+ / {
        level = match($0, /[^#]/) - 1
        if (section != "" && level <= section_level) section = ""
        if (shading && level <= shading_level) shading = 0
        if (match($0, /^#+ `[a-z_]+/)) {
          section = substr($0, RSTART, RLENGTH); sub(/^#+ `/, "", section); section_level = level
        }
        if ($0 ~ /Shading kinds/) { shading = 1; shading_level = level }
        next
      }
      /^\|/ {
        split($0, cell, "|"); first = cell[2]
        while (match(first, /`[A-Za-z_]+`/)) {
          word = substr(first, RSTART + 1, RLENGTH - 2); first = substr(first, RSTART + RLENGTH)
          if (section != "") print section, word
          if (shading) print "shading", word
        }
      }' "$doc" | sort -u >documented.txt
    while read -r kind name rest; do
      if [[ $kind == statement ]]; then
        grep -q "^#\+ \`$name" "$doc" || missing "a section whose heading starts with \`$name"
        for key in $rest; do
          grep -qxF "$name $key" documented.txt ||
            missing "a table row for the key $key in the section of \`$name"
        done
      else
        grep -qxF "shading $name" documented.txt ||
          missing "a table row for the shading kind $name under \"Shading kinds\""
      fi
    done <accepted.txt
    # The complete example: valid, and using every statement and key.
    awk '/^<!-- complete example -->/ { marker = 1; next }
         marker && /^```/ { if (inside) exit; inside = 1; next }
         inside { print }' "$doc" >example.scene
    # Its image texture is the gallery's, at the path the example gives.
    ln -sfn "$(cd "$(dirname "$doc")" && pwd)/images/textures" textures
    if [[ ! -s example.scene ]]; then
      missing "a complete example (a code block after <!-- complete example -->)"
    elif ! "$program" example.scene >/dev/null; then
      missing "a valid complete example (the reader's error is above)"
    else
      sed 's/#.*//' example.scene | awk '{ print "statement", $1; for (i = 2; i <= NF; i++) if (split($i, kv, "=") == 2) print "key", kv[1] }' |
        sort -u >used.txt
      while read -r kind name rest; do
        [[ $kind == statement ]] || continue
        grep -qxF "statement $name" used.txt || missing "the statement $name in its complete example"
        for key in $rest; do
          grep -qxF "key $key" used.txt || missing "the key $key in its complete example"
        done
      done <accepted.txt
    fi
    ((fail)) || echo "reference_test: $doc documents every statement, key and shading kind the reader accepts"
    ;;
  *)
    echo "usage: reference_test.bash options DOC PROGRAM [BASE] | scene DOC KEYS_PROGRAM" >&2
    exit 2
    ;;
esac
exit $fail
