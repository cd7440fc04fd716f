#!/usr/bin/env bash
# glint-compare's page in a real browser (headless Chromium), and glint-compare's refusals:
#
#   viewer_test.bash CASE SCRATCH REPO RENDER_REPORT RENDER_FAST COMPARE SCREENSHOT_CHECK
#
# CASE is one of the functions below named case_*; it works in the directory SCRATCH (emptied
# first). REPO is the source tree (for the test scene); RENDER_REPORT
# and RENDER_FAST are glint-render-report and glint-render-fast, COMPARE is glint-compare and
# SCREENSHOT_CHECK is glint-viewer-screenshot-check.
#
# The page says what happened through attributes, which --dump-dom shows after its script ran:
# <body data-state="done" data-images="N" data-loaded="N" data-failed="0">, and one table row
# per variant with data-variant="NAME". Exit status 0 on success, 77 when Chromium is missing
# (a test installs nothing), or for the EXR case in a build without
# OpenEXR (ctest's SKIP_RETURN_CODE: reported as skipped, with the reason on stderr, never as
# a pass), 1 on a failure with the reason on stderr.
# GLINT_VIEWER_BROWSER names another program than chromium (a missing one skips).
set -euo pipefail
case_name=$1 scratch=$2 repo=$3 render_report=$4 render_fast=$5 compare=$6 screenshot_check=$7

fail() {
  echo "FAIL ($case_name): $*" >&2
  exit 1
}

rm -rf "$scratch"
mkdir -p "$scratch"
cd "$scratch"

scene=$repo/tests/cli/scenes/tiny.scene
size=(--width 48 --height 32 --max-depth 3 --threads 1 --quiet)

# A reference and two variants of the tiny scene, and their manifest: report first, the
# baseline; fast second, at twice the samples, as an equal-time comparison would give it.
render_comparison() {
  "$render_fast" "$scene" "${size[@]}" --spp 64 --seed 1000003 --hdr reference.pfm -o reference.png
  "$render_report" "$scene" "${size[@]}" --spp 4 --hdr report.pfm -o report.png
  "$render_fast" "$scene" "${size[@]}" --spp 8 --hdr fast.pfm -o fast.png
  {
    printf '# scene, variant, image, CPU seconds, spp, description\n'
    printf 'reference\ttiny\treference.pfm\tfast at 64 spp\n'
    printf 'variant\ttiny\treport\treport.pfm\t0.02\t4\tthe report'"'"'s renderer\n'
    printf 'variant\ttiny\tfast\tfast.pfm\t0.02\t8\t<b>not markup</b> & "quotes"\n'
  } >manifest.tsv
  "$compare" manifest.tsv -o page --title "viewer test" >compare.log 2>&1 ||
    { cat compare.log >&2; fail "glint-compare failed"; }
}

browser=""
find_browser() {
  browser=$(command -v "${GLINT_VIEWER_BROWSER:-chromium}" || true)
  [[ -n $browser ]]
}
need_browser() {
  find_browser && return 0
  echo "SKIPPED ($case_name): Chromium is not installed (Debian package chromium:" \
    "scripts/install-deps --browser); the page was not tested in a browser" >&2
  exit 77
}

# browse URL OPTION...: runs headless Chromium on URL. Root (as in CI) needs --no-sandbox; a
# profile of its own keeps runs from sharing state or locks. The virtual time budget lets the
# page's script and every image load run to the end before the DOM or screenshot is taken.
browse() {
  local url=$1
  shift
  timeout 90 "$browser" --headless --no-sandbox --disable-gpu --no-first-run \
    --disable-extensions --user-data-dir="$scratch/profile" --window-size=1200,800 \
    --virtual-time-budget=10000 "$@" "$url" 2>>browser.log ||
    { tail -n 20 browser.log >&2; fail "chromium failed on $url"; }
}

# body_attribute NAME: the value of data-NAME on <body> in dom.html.
body_attribute() {
  grep -o '<body[^>]*>' dom.html | grep -o "data-$1=\"[^\"]*\"" | cut -d'"' -f2 || true
}

case_page() {
  render_comparison
  need_browser
  browse "file://$scratch/page/index.html" --dump-dom >dom.html
  [[ $(body_attribute state) == "done" ]] ||
    fail "the page's script did not finish: $(grep -o '<body[^>]*>' dom.html || echo 'no <body>')"
  [[ $(body_attribute images) == 5 ]] || fail "data-images='$(body_attribute images)', expected 5"
  [[ $(body_attribute loaded) == 5 ]] || fail "data-loaded='$(body_attribute loaded)', expected 5"
  [[ $(body_attribute failed) == 0 ]] || fail "data-failed='$(body_attribute failed)', expected 0"
  local listed
  listed=$(grep -o 'data-variant="[^"]*"' dom.html | cut -d'"' -f2 | tr '\n' ' ')
  [[ $listed == "report fast " ]] || fail "variant rows: '$listed', expected 'report fast '"
  [[ $(grep -o 'data-entry="reference"' dom.html | wc -l) == 1 ]] || fail "no single reference row"
  grep -q 'data-scene="tiny"' dom.html || fail "no scene 'tiny' in the scene list"
  # The description is text, not markup, however it is spelled.
  grep -q '&lt;b&gt;not markup&lt;/b&gt; &amp; "quotes"' dom.html ||
    fail "the description with markup characters is not shown as text"

  # The screenshot shows the selected image (report, the baseline): its exact colours are on
  # the screen, which neither a blank page nor one whose images failed has.
  browse "file://$scratch/page/index.html" --screenshot="$scratch/shot.png" >/dev/null
  local stats
  stats=$("$screenshot_check" shot.png page/tiny/variant-report.png) ||
    fail "cannot read the screenshot"
  echo "screenshot: $stats"
  [[ $stats =~ colours=([0-9]+).*dominant=([0-9.]+).*found=([0-9.]+) ]] || fail "bad check output"
  ((BASH_REMATCH[1] >= 100)) || fail "the screenshot has ${BASH_REMATCH[1]} colours: blank"
  awk -v d="${BASH_REMATCH[2]}" 'BEGIN { exit !(d < 0.9) }' ||
    fail "one colour covers ${BASH_REMATCH[2]} of the screenshot: blank"
  awk -v f="${BASH_REMATCH[3]}" 'BEGIN { exit !(f >= 0.95) }' ||
    fail "only ${BASH_REMATCH[3]} of the image's colours are on the screen: it is not shown"
}

# Keys and a click, sent to the page's own code: a copy of the page with a script at the end
# that presses keys and writes down the image shown after each, for --dump-dom to show.
case_keys() {
  render_comparison
  need_browser
  sed 's|</body>|<script src="press-keys.js"></script></body>|' page/index.html >page/keys.html
  cat >page/press-keys.js <<'EOF'
"use strict";
const shown = [];
const image = document.getElementById("image");
const scale = () => Number(/scale\(([0-9.e+-]+)\)/.exec(image.style.transform)[1]);
const note = () => shown.push(image.getAttribute("src").replace("tiny/", ""));
const press = (key) => {
  document.dispatchEvent(new KeyboardEvent("keydown", { key, bubbles: true }));
  note();
};
note();
for (const key of ["ArrowRight", "e", " ", " ", "e", "r", "2", "b", "1", " ", "ArrowLeft"]) {
  press(key);
}
const fitted = scale();
press("+");
const zoomed = scale();
press("0");
document.querySelector('tr[data-variant="fast"]').click();
note();
document.body.dataset.shown = shown.join(" ");
document.body.dataset.zoom = (zoomed / fitted).toFixed(3) + " " + (scale() / fitted).toFixed(3);
EOF
  browse "file://$scratch/page/keys.html" --dump-dom >dom.html
  local expected="variant-report.png variant-fast.png error-fast.png reference.png error-fast.png"
  expected+=" variant-fast.png reference.png variant-fast.png variant-fast.png variant-report.png"
  expected+=" variant-fast.png reference.png reference.png reference.png variant-fast.png"
  [[ $(body_attribute shown) == "$expected" ]] ||
    fail "images shown after the keys: '$(body_attribute shown)', expected '$expected'"
  [[ $(body_attribute zoom) == "1.414 1.000" ]] ||
    fail "zoom after + and 0: '$(body_attribute zoom)', expected '1.414 1.000'"
}

# The check is not vacuous: with one image gone, the page says so.
case_missing_image() {
  render_comparison
  need_browser
  rm page/tiny/error-fast.png
  browse "file://$scratch/page/index.html" --dump-dom >dom.html
  [[ $(body_attribute state) == "done" ]] || fail "the page's script did not finish"
  [[ $(body_attribute failed) == 1 ]] || fail "data-failed='$(body_attribute failed)', expected 1"
  [[ $(body_attribute loaded) == 4 ]] || fail "data-loaded='$(body_attribute loaded)', expected 4"
  grep -q 'Could not load 1 of 5 images: tiny/error-fast.png' dom.html ||
    fail "the page does not name the missing image"
  grep -q '<tr data-variant="fast" class="failed"' dom.html || fail "the row of fast is not marked"
}

# expect_refusal WHAT PATTERN ARGS...: glint-compare exits with 1, says PATTERN on stderr and
# writes no page.
expect_refusal() {
  local what=$1 pattern=$2 status=0
  shift 2
  rm -rf out
  "$compare" "$@" -o out 2>err.log || status=$?
  ((status == 1)) || fail "$what: exit status $status, expected 1"
  grep -Eq "$pattern" err.log || fail "$what: stderr '$(cat err.log)' does not match '$pattern'"
  [[ ! -e out/index.html ]] || fail "$what: a page was written"
}

# write_manifest FILE LINE...: one manifest line per argument, '|' standing for a tab.
write_manifest() {
  local file=$1
  shift
  printf '%s\n' "$@" | tr '|' '\t' >"$file"
}

case_errors() {
  render_comparison
  "$render_fast" "$scene" --width 24 --height 16 --spp 1 --quiet --hdr small.pfm -o small.png
  write_manifest missing.tsv "reference|tiny|reference.pfm" "variant|tiny|fast|missing.pfm|1|8"
  expect_refusal "missing image" "missing.tsv:2: .*missing.pfm" missing.tsv
  write_manifest size.tsv "reference|tiny|reference.pfm" "variant|tiny|fast|small.pfm|1|8"
  expect_refusal "size mismatch" \
    "size.tsv:2: .*small.pfm is 24x16, the reference .* is 48x32" size.tsv
  write_manifest cpu.tsv "reference|tiny|reference.pfm" "variant|tiny|fast|fast.pfm|soon|8"
  expect_refusal "bad CPU time" "cpu.tsv:2: CPU seconds must be a number" cpu.tsv
  write_manifest fields.tsv "# comment" "" "reference|tiny" "variant|tiny|fast|fast.pfm|1|8"
  expect_refusal "too few fields" "fields.tsv:3: a reference line has 3 to 4" fields.tsv
  write_manifest noref.tsv "variant|tiny|fast|fast.pfm|1|8"
  expect_refusal "no reference" "noref.tsv:1: scene 'tiny' has no reference" noref.tsv
  write_manifest name.tsv "reference|../tiny|reference.pfm"
  expect_refusal "scene name with a slash" "name.tsv:1: scene name '../tiny'" name.tsv
  write_manifest twice.tsv "reference|tiny|reference.pfm" "variant|tiny|fast|fast.pfm|1|8" \
    "variant|tiny|fast|fast.pfm|1|8"
  expect_refusal "a variant twice" \
    "twice.tsv:3: variant 'fast' of scene 'tiny' is already at twice.tsv:2" twice.tsv
  expect_refusal "no manifest" \
    "cannot read the manifest nowhere.tsv: No such file or directory" nowhere.tsv
  # Images that would take all the memory or never end: refused from their first bytes (the
  # readers' memory is measured in tests/unit/image_reader_test.cpp).
  printf 'PF\n8192 8192\n-1.0\n' >claims.pfm
  write_manifest claims.tsv "reference|tiny|claims.pfm"
  expect_refusal "a header claiming more than the file" \
    "claims.tsv:1: .*claims.pfm: truncated PFM file: its header claims 8192x8192 pixels" \
    claims.tsv
  write_manifest zero.tsv "reference|tiny|/dev/zero"
  expect_refusal "/dev/zero" "zero.tsv:1: /dev/zero: not a colour PFM file" zero.tsv
  # Manifests that would do the same are refused at the bound they pass (16 MiB, lines of 65536
  # characters), named with their line.
  expect_refusal "/dev/zero as the manifest" \
    "^glint-compare: error: /dev/zero:1: line contains a NUL byte" /dev/zero
  head -c 100000 /dev/zero | tr '\0' a >long.tsv
  expect_refusal "a line of 100000 characters" \
    "^glint-compare: error: long.tsv:1: line is longer than 65536 characters" long.tsv
  expect_refusal "a line without end" \
    "^glint-compare: error: /dev/fd/[0-9]+:1: line is longer than 65536 characters" \
    <(tr '\0' a </dev/zero)
  # Lines of 12 bytes: byte 2^24 + 1 is on line floor(2^24 / 12) + 1 = 1398102.
  expect_refusal "comments without end" \
    "^glint-compare: error: /dev/fd/[0-9]+:1398102: file is larger than 16 MiB" \
    <(yes '# a comment')
  truncate -s 17M large.tsv
  expect_refusal "a manifest of 17 MiB" "^glint-compare: error: large.tsv: file is larger than 16 MiB" \
    large.tsv

  # A failed run leaves an earlier page as it was.
  cp -r page before
  "$compare" missing.tsv -o page 2>/dev/null && fail "glint-compare accepted a missing image"
  diff -r before page >/dev/null || fail "a failed run changed the earlier page"
}

# EXR results read as PFM ones are: the same renders as float32 EXR give the same page, byte
# for byte. Skipped (77) in a build without OpenEXR, where glint-compare refuses .exr.
case_exr() {
  if ! "$compare" --help | grep -q "PFM or OpenEXR"; then
    echo "SKIPPED ($case_name): glint-compare was built without OpenEXR" \
      "(scripts/install-deps --exr, then configure again)" >&2
    exit 77
  fi
  "$render_fast" "$scene" "${size[@]}" --spp 64 --seed 1000003 --hdr reference.pfm \
    --exr reference.exr -o reference.png
  "$render_report" "$scene" "${size[@]}" --spp 4 --hdr report.pfm --exr report.exr -o report.png
  write_manifest pfm.tsv "reference|tiny|reference.pfm" "variant|tiny|report|report.pfm|0.02|4"
  write_manifest exr.tsv "reference|tiny|reference.exr" "variant|tiny|report|report.exr|0.02|4"
  "$compare" pfm.tsv -o from-pfm >/dev/null
  "$compare" exr.tsv -o from-exr >/dev/null
  diff -r from-pfm from-exr >/dev/null || fail "the pages from PFM and from EXR differ"
}

"case_${case_name//-/_}"
echo "PASS ($case_name)"
