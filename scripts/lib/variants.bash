# Shared by bench/run-all and scripts/update-docs (sourced, not run): the named variants as
# the tables show them, read from the variants.tsv that configuring glint writes
# (cmake/GlintVariants.cmake runs cmake/list_variants.cpp over include/glint/variants.hpp).
# Its lines are "variant<TAB>NAME<TAB>same|different<TAB>DESCRIPTION", in the order of
# glint::variants::all, then "default<TAB>NAME", then
# "renderer<TAB>NAME<TAB>scalar|wavefront<TAB>CLASS" for each execution model a variant renders
# with (CLASS: the C++ class template of that execution model), then "estimator<TAB>NAME" for
# each variant glint-render holds (its --estimator choices, the default first), then
# "blind_spot<TAB>NAME", the one it chooses for a scene the path tracer is blind to.

# glint_variants_check TSV: fails, saying why, unless TSV is such a file with `report` first.
glint_variants_check() {
  local tsv=$1
  if [[ ! -s $tsv ]]; then
    echo "no $tsv: configure a build first (cmake -S SOURCE -B BUILD writes BUILD/variants.tsv)" >&2
    return 1
  fi
  awk -F'\t' '
    $1 == "variant" && NF == 4 && $2 ~ /^[a-z0-9_]+$/ && ($3 == "same" || $3 == "different") &&
      $4 != "" { if (++variants == 1) first = $2; next }
    $1 == "default" && NF == 2 { defaults++; next }
    $1 == "renderer" && NF == 4 && ($3 == "scalar" || $3 == "wavefront") && $4 ~ /^glint::[A-Za-z]+$/ { next }
    $1 == "estimator" && NF == 2 && $2 ~ /^[a-z0-9_]+$/ { next }
    $1 == "blind_spot" && NF == 2 && $2 ~ /^[a-z0-9_]+$/ { next }
    { printf "%s:%d: not a variant line: %s\n", FILENAME, FNR, $0 > "/dev/stderr"; bad = 1 }
    END {
      if (bad) exit 1
      if (first != "report") { printf "%s: the first variant must be report, not \"%s\"\n", FILENAME, first > "/dev/stderr"; exit 1 }
      if (defaults != 1) { printf "%s: needs one default line\n", FILENAME > "/dev/stderr"; exit 1 }
    }' "$tsv"
}

# glint_variant_rows TSV: "NAME<TAB>DESCRIPTION" per variant, in table order. The description
# is the variant's own, followed by " (different image)" for an ablation that converges to
# another image than `report` (VariantInfo::same_image_as_report is false).
glint_variant_rows() {
  awk -F'\t' '$1 == "variant" { print $2 "\t" $4 ($3 == "different" ? " (different image)" : "") }' "$1"
}

# glint_default_variant TSV: the variant plain glint-render renders with unless the scene or
# --estimator asks for another.
glint_default_variant() {
  awk -F'\t' '$1 == "default" { print $2 }' "$1"
}

# glint_render_estimators TSV: the variants glint-render holds (--estimator), one per line, the
# default first.
glint_render_estimators() {
  awk -F'\t' '$1 == "estimator" { print $2 }' "$1"
}
