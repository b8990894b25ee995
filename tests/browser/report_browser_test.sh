#!/usr/bin/env bash
# Browser test of the HTML report (issue 7): headless Chromium renders DIR/report.html of the
# reference-IMU demo inside `unshare -n` (no network at all), writes DIR/report.png next to the
# report, and the test checks that the page loads without console messages or resource loads,
# and that the rendered DOM holds the title, the summary table, every plot and the sections;
# that the verdict is the first section and each of its findings has a cause and a remedy; and
# that at a phone's width (390 px) the page does not scroll sideways (report-phone.png).
#
#   report_browser_test.sh IMUNOISE_BINARY SOURCE_DIR [WORK_DIR]
# WORK_DIR (default: a new temp dir) is emptied and receives the demo (demo/: the report and
# report.png), the dumped DOM (report.dom.html) and Chromium's log (report.chromium.log). ctest
# passes <build>/tests/browser so the PNG can be looked at after a run.
# IMUNOISE_BROWSER_REPORT_DIR=DIR checks an existing report directory instead of building the
# demo (DIR/report.png is written). IMUNOISE_BROWSER_WINDOW_HEIGHT sets the PNG height (default
# 10000 px: the demo's page is ~9000 px tall at 1280 px width; the screenshot is the viewport).
# Exit: 0 pass, 1 fail, 77 skipped (no chromium, or `unshare -n` not permitted).
#
# Recipe that works with Debian 12's chromium 156.0.8078.79: plain --headless (the new headless
# mode, the only one left in the chromium binary since 132). One invocation does both the DOM
# dump (stdout) and the screenshot (viewport only: the window height is the PNG height):
#   unshare -n chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --no-first-run \
#     --disable-background-networking --disable-component-update --disable-sync \
#     --disable-extensions --user-data-dir=FRESH_DIR --enable-logging=stderr --v=0 \
#     --vmodule=file_url_loader_factory=1,network_delegate=1 --virtual-time-budget=5000 \
#     --window-size=1280,H --screenshot=DIR/report.png --dump-dom file:///…/report.html
# - --no-sandbox: Chromium refuses to run as root without it (and the sandbox needs user
#   namespaces we do not have inside unshare); the page is our own local file, network-isolated.
# - Console: with --enable-logging=stderr every console message of the page (console.log/warn/
#   error alike, and uncaught exceptions as "Uncaught …") is one line
#   `[pid:tid:time:INFO:CONSOLE:LINE] "text", source: URL (LINE)`; this log level does not say
#   which console method was used, so ANY console line of the page fails the test (the report
#   has no script and must print nothing). Lines whose source is one of Chromium's own WebUI
#   pages (chrome://…, e.g. "Slow network is detected" from the omnibox popup, seen when run as
#   a non-root user) are not the page's and are ignored.
# - Failed resource loads are not logged at --v=0. The two vmodule switches make Chromium log
#   each file:// load ("FileURLLoader::Start: URL") and each network request
#   ("NetworkDelegate::NotifyBeforeURLRequest: URL"). A self-contained report loads nothing but
#   itself, so any other file load (missing or not) or network request of the page fails the
#   test. Chromium's own background requests (component updater, network time, spell-check
#   dictionary) still show up despite the --disable-* switches and are ignored by URL.
# - Everything else on stderr (D-Bus, vaapi, GPU sandbox warnings, the wrapper's
#   "/usr/bin/chromium: 9: [: …: unexpected operator") is not about the page and is not looked at.
# - The detector is proven on every run: a control page with console.error("imunoise-control"),
#   <img src="missing.png"> and an http:// image is rendered first; if any of the three is not
#   reported, the test FAILS.
# About 2 s per Chromium run; the demo (simulate, analyze, drift, report) dominates the time.
set -uo pipefail

if [ $# -lt 2 ]; then
  echo "usage: $0 IMUNOISE_BINARY SOURCE_DIR [WORK_DIR]" >&2
  exit 2
fi
BIN="$1"
SRC="$2"
WORK="${3:-}"
WINDOW_HEIGHT="${IMUNOISE_BROWSER_WINDOW_HEIGHT:-10000}"
MIN_PNG_BYTES=60000   # a blank 1280-wide page is ~10 KB; six plots and a table are far more

skip() {
  echo "SKIPPED: $*"
  exit 77
}
FAILURES=0
fail() {
  echo "FAIL: $*"
  FAILURES=$((FAILURES + 1))
}
ok() { echo "ok: $*"; }

# --- prerequisites: chromium and a network namespace -------------------------------------------
# IMUNOISE_CHROMIUM=PATH uses that binary only (and skips if it is not there).
CHROMIUM=""
if [ -n "${IMUNOISE_CHROMIUM:-}" ]; then
  [ -x "$IMUNOISE_CHROMIUM" ] && CHROMIUM="$IMUNOISE_CHROMIUM"
elif command -v chromium >/dev/null 2>&1; then
  CHROMIUM="$(command -v chromium)"
elif [ -x /usr/bin/chromium ]; then
  CHROMIUM=/usr/bin/chromium
fi
if [ -z "$CHROMIUM" ]; then
  skip "chromium is not installed (CI installs it with apt-get install chromium;" \
    "run: sudo apt-get install -y chromium)"
fi
UNSHARE=()
if unshare -n true 2>/dev/null; then
  UNSHARE=(unshare -n)
elif unshare -r -n true 2>/dev/null; then
  UNSHARE=(unshare -r -n)   # not root: a user namespace mapped to root, then a network one
else
  skip "'unshare -n' is not permitted here (needs root or unprivileged user namespaces), and" \
    "Chromium is only run without network access"
fi

if [ -z "$WORK" ]; then
  WORK="$(mktemp -d "${TMPDIR:-/tmp}/imunoise-browser.XXXXXX")"
else
  rm -rf "$WORK"
  mkdir -p "$WORK"
fi
WORK="$(cd "$WORK" && pwd)"
echo "work dir: $WORK"

# --- rendering and the page-problem detector ----------------------------------------------------
# render PAGE PNG DOM LOG: one Chromium run (fresh profile, no network): DOM on DOM, PNG, log.
render() {
  local page="$1" png="$2" dom="$3" log="$4" profile
  profile="$(mktemp -d "$WORK/chrome-profile.XXXXXX")"
  timeout -k 5 120 "${UNSHARE[@]}" "$CHROMIUM" --headless --no-sandbox --disable-gpu \
    --hide-scrollbars --no-first-run --no-default-browser-check --disable-background-networking \
    --disable-component-update --disable-sync --disable-extensions --disable-default-apps \
    --user-data-dir="$profile" --enable-logging=stderr --v=0 \
    --vmodule=file_url_loader_factory=1,network_delegate=1 --virtual-time-budget=5000 \
    ${EXTRA_FLAGS:-} --window-size="${WINDOW_WIDTH:-1280},$WINDOW_HEIGHT" --screenshot="$png" \
    --dump-dom "file://$page" \
    >"$dom" 2>"$log"
  local rc=$?
  rm -rf "$profile"
  return $rc
}

# url_path URL: the local path of a file:// URL (percent-decoded).
url_path() {
  local p="${1#file://}"
  p="${p%%[?#]*}"
  printf '%b' "${p//%/\\x}"
}

# page_problems LOG PAGE: one line per console message, extra/missing file load and network
# request that came from the page PAGE.
page_problems() {
  local log="$1" page="$2" line url path
  # Chromium's own WebUI pages (chrome://omnibox-popup…) log too ("Slow network is detected…"):
  # only the page's console lines count.
  grep -E ':CONSOLE[:(]' "$log" |
    grep -v -E 'source: (chrome|chrome-untrusted|chrome-extension|devtools)://' |
    sed 's/^\[[^]]*\] */console: /'
  while IFS= read -r url; do
    path="$(url_path "$url")"
    [ "$path" = "$page" ] && continue
    if [ -e "$path" ]; then
      echo "resource load (a self-contained page loads nothing): $url"
    else
      echo "failed resource load (file not found): $url"
    fi
  done < <(grep -o 'FileURLLoader::Start: .*' "$log" | sed 's/^FileURLLoader::Start: //')
  while IFS= read -r url; do
    case "$url" in
      # Chromium's own background services, not the page.
      http*://update.googleapis.com/service/update2/* | http*://clients2.google.com/time/* | \
        http*://redirector.gvt1.com/edgedl/chrome/dict/* | http*://*.gvt1.com/edgedl/*)
        continue ;;
    esac
    echo "network request (fails: no network): $url"
  done < <(grep -o 'NotifyBeforeURLRequest: .*' "$log" | sed 's/^NotifyBeforeURLRequest: //')
}

# --- 1. the detector must see the faults of a control page --------------------------------------
CONTROL="$WORK/control"
mkdir -p "$CONTROL"
cat >"$CONTROL/control.html" <<'EOF'
<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>control</title></head>
<body><h1>control page with three faults</h1>
<img src="missing.png" alt="missing">
<img src="http://imunoise-control.invalid/remote.png" alt="remote">
<script>console.error("imunoise-control");</script>
</body></html>
EOF
if ! render "$CONTROL/control.html" "$CONTROL/control.png" "$CONTROL/control.dom.html" \
  "$CONTROL/control.chromium.log"; then
  echo "FAIL: chromium did not render the control page; its log:"
  tail -n 30 "$CONTROL/control.chromium.log"
  exit 1
fi
CONTROL_PROBLEMS="$(page_problems "$CONTROL/control.chromium.log" "$CONTROL/control.html")"
control_ok=1
for expected in '"imunoise-control"' 'file not found.*/missing.png' \
  'network request.*imunoise-control.invalid'; do
  if ! grep -q -- "$expected" <<<"$CONTROL_PROBLEMS"; then
    echo "FAIL: the detector missed a fault of the control page (expected /$expected/)"
    control_ok=0
  fi
done
if [ "$control_ok" -ne 1 ]; then
  echo "detector output for the control page:"
  printf '%s\n' "$CONTROL_PROBLEMS"
  echo "(Chromium's log format may have changed; see $CONTROL/control.chromium.log)"
  exit 1
fi
ok "detector reports the control page's console.error, missing image and network request"

# --- 2. the report of the reference-IMU demo ----------------------------------------------------
if [ -n "${IMUNOISE_BROWSER_REPORT_DIR:-}" ]; then
  DIR="$(cd "$IMUNOISE_BROWSER_REPORT_DIR" && pwd)"
  echo "checking the existing report in $DIR"
else
  DIR="$WORK/demo"
  mkdir -p "$DIR"
  run() {
    echo "+ imunoise $*"
    if ! "$BIN" "$@" >"$WORK/last_command.log" 2>&1; then
      echo "FAIL: imunoise $* failed:"
      tail -n 30 "$WORK/last_command.log"
      rm -f "$DIR/recording.csv"
      exit 1
    fi
  }
  # The demo's settings (tools/demo: 8 h at 50 Hz, seed 42), with --bootstrap 0 so the analysis
  # takes seconds instead of minutes (the bootstrap changes the intervals, not what is plotted).
  start=$SECONDS
  run simulate "$SRC/configs/reference-imu.yaml" --duration 8h --rate 50 --seed 42 \
    -o "$DIR/recording.csv"
  run analyze "$DIR/recording.csv" -o "$DIR" --bootstrap 0 \
    --truth "$SRC/configs/reference-imu.yaml"
  run drift "$DIR/recording.csv" --model "$DIR/model.yaml" --heading 0 -o "$DIR/drift"
  rm -f "$DIR/recording.csv"   # 200 MB; not needed by the report
  run report "$DIR"
  echo "demo and report built in $((SECONDS - start)) s"
fi

REPORT="$DIR/report.html"
PNG="$DIR/report.png"
DOM="$WORK/report.dom.html"
LOG="$WORK/report.chromium.log"
if [ ! -s "$REPORT" ]; then
  echo "FAIL: $REPORT was not written"
  exit 1
fi
rm -f "$PNG"
if ! render "$REPORT" "$PNG" "$DOM" "$LOG"; then
  fail "chromium exited with an error on $REPORT (log: $LOG)"
  tail -n 30 "$LOG"
fi

# (c) console messages and resource loads
PROBLEMS="$(page_problems "$LOG" "$REPORT")"
if [ -n "$PROBLEMS" ]; then
  fail "the page produced console messages or resource loads:"
  sed "s/^/  /" <<<"$PROBLEMS"
else
  ok "no console message, no resource load besides the page"
fi

# (a) the screenshot next to the report
if [ ! -s "$PNG" ]; then
  fail "no screenshot $PNG"
else
  magic="$(od -An -tx1 -N8 "$PNG" | tr -d ' \n')"
  size="$(stat -c %s "$PNG")"
  width=$((16#$(od -An -tx1 -j16 -N4 "$PNG" | tr -d ' \n')))
  height=$((16#$(od -An -tx1 -j20 -N4 "$PNG" | tr -d ' \n')))
  if [ "$magic" != 89504e470d0a1a0a ]; then
    fail "$PNG is not a PNG (magic $magic)"
  elif [ "$size" -lt "$MIN_PNG_BYTES" ]; then
    fail "$PNG is only $size bytes: blank or nearly empty page"
  else
    ok "screenshot $PNG: ${width}x${height}, $size bytes"
  fi
fi

# (b) the rendered DOM
if [ ! -s "$DOM" ]; then
  fail "chromium dumped no DOM"
fi
FLAT="$WORK/report.dom.flat"
tr '\n\r' '  ' <"$DOM" >"$FLAT"
# element FILE START_ERE END: text from the first match of START_ERE to the next END (inclusive).
element() {
  awk -v re="$2" -v end="$3" '{
    if (match($0, re)) {
      rest = substr($0, RSTART); e = index(rest, end)
      if (e) print substr(rest, 1, e + length(end) - 1)
    }
  }' "$1"
}

title="$(element "$FLAT" '<title>' '</title>')"
if [[ "$title" == "<title>imunoise report"* ]]; then
  ok "title: $title"
else
  fail "the title does not start with 'imunoise report': '${title:-no <title>}'"
fi

table="$(element "$FLAT" '<table[^>]* id="summary-table"' '</table>')"
if [ -z "$table" ]; then
  fail 'no <table id="summary-table">'
else
  rows="$(awk '{
    n = split($0, parts, "<tr"); c = 0
    for (i = 2; i <= n; ++i) if (index(parts[i], "<td")) ++c
    print c
  }' <<<"$table")"
  if [ "$rows" -ge 6 ]; then
    ok "summary table with $rows data rows"
  else
    fail "summary table has $rows data rows (at least one per axis: 6 expected)"
  fi
  for axis in gyro accel; do
    grep -qi "$axis" <<<"$table" || fail "summary table never mentions $axis"
  done
fi

FIGURES=(allan-gyro allan-accel psd-gyro psd-accel sampling-intervals)
if [ -z "${IMUNOISE_BROWSER_REPORT_DIR:-}" ] || [ -d "$DIR/drift" ]; then
  FIGURES+=(drift-horizontal)
fi
for name in "${FIGURES[@]}"; do
  figure="$(element "$FLAT" "<figure[^>]* id=\"fig-$name\"" '</figure>')"
  if [ -z "$figure" ]; then
    fail "no <figure id=\"fig-$name\">"
    continue
  fi
  problems=()
  grep -q '<svg' <<<"$figure" || problems+=("no inline <svg>")
  caption="$(element <(printf '%s\n' "$figure") '<figcaption' '</figcaption>')"
  [ -n "$caption" ] || problems+=("no <figcaption>")
  grep -q "href=\"plots/$name.csv\"" <<<"$caption" ||
    problems+=("no link to plots/$name.csv in the caption")
  [ -s "$DIR/plots/$name.csv" ] || problems+=("plots/$name.csv missing or empty next to the report")
  if [ ${#problems[@]} -eq 0 ]; then
    ok "figure fig-$name: inline svg, caption linking plots/$name.csv (present)"
  else
    fail "figure fig-$name: $(IFS=';'; echo "${problems[*]}")"
  fi
done

# Every relative link of the page resolves next to the report.
while IFS= read -r href; do
  target="${href%%[?#]*}"
  [ -z "$target" ] && continue
  [ -e "$DIR/$(printf '%b' "${target//%/\\x}")" ] || fail "link to a missing file: $href"
done < <(grep -o 'href="[^"]*"' "$FLAT" | sed 's/^href="//; s/"$//' |
  grep -v -E '^(#|[a-zA-Z][a-zA-Z0-9+.-]*:|//)' | sort -u)

# The verdict is the first section after the header (issue 23), and every finding in it names
# a cause and a remedy.
first_section="$(awk '{
  h = index($0, "</header>"); if (!h) exit
  rest = substr($0, h); if (match(rest, /<section[^>]*>/)) print substr(rest, RSTART, RLENGTH)
}' "$FLAT")"
if [[ "$first_section" == *'id="verdict"'* ]]; then
  ok "the first section after the header is the verdict"
else
  fail "the first section after the header is not the verdict: '${first_section:-none}'"
fi
verdict="$(element "$FLAT" '<section[^>]* id="verdict"' '</section>')"
items="$(sed 's/<li>/\n<li>/g' <<<"$verdict" | grep '^<li>' | sed 's/<\/li>.*//')"
n_items=0
while IFS= read -r item; do
  [ -z "$item" ] && continue
  n_items=$((n_items + 1))
  if ! grep -q 'class="cause">Cause: [^<]' <<<"$item" ||
    ! grep -q 'class="remedy">Remedy: [^<]' <<<"$item"; then
    fail "a verdict finding lacks a cause or a remedy: ${item:0:200}"
  fi
done <<<"$items"
ok "verdict: $n_items finding(s), each with a cause and a remedy"
for id in verdict-gyro verdict-accel; do
  if [ -n "$(element "$FLAT" "<table[^>]* id=\"$id\"" '</table>')" ]; then
    ok "verdict matrix #$id"
  else
    fail "no verdict matrix <table id=\"$id\">"
  fi
done

for section in findings exports commands; do
  if [ -n "$(element "$FLAT" "<section[^>]* id=\"$section\"" '</section>')" ]; then
    ok "section #$section"
  else
    fail "no <section id=\"$section\">"
  fi
done

# Self-contained: nothing in the markup that a browser would fetch.
LOADING_TAGS='script|img|iframe|frame|embed|object|source|track|video|audio|link|image|use|input'
external="$(grep -o -E "<($LOADING_TAGS)[[:space:]][^>]*(src|href|data)=\"[^\"#][^\"]*\"" "$FLAT" |
  grep -v -E '(src|href|data)="data:' | head -n 5)"
[ -z "$external" ] || fail "the page references external resources: $external"
css_urls="$(grep -o -E "@import[^;]*|url\([^)]*\)" "$FLAT" |
  grep -v -E "^url\( *['\"]?(#|data:)" | head -n 5)"
[ -z "$css_urls" ] || fail "the page's CSS imports or references a URL: $css_urls"

# --- 3. phone width ------------------------------------------------------------------------------
# The page at a phone's CSS width (390 px). Headless Chromium lays a window out at least 500 px
# wide whatever --window-size says (the PNG is only cropped), so the test's own probe page holds
# the report in a 390 px wide iframe — whose viewport the report's media queries see — and a
# script that measures the report's layout there and writes the numbers into the probe's DOM
# (--allow-file-access-from-files lets the file:// probe read the file:// report). The page must
# not scroll sideways (wide tables scroll inside their own box) and the verdict must fit. The
# report itself is not changed and still has no script.
PHONE_WIDTH=390
PROBE="$WORK/phone-probe.html"
PHONE_PNG="$DIR/report-phone.png"
cat >"$PROBE" <<EOF
<!DOCTYPE html><html><head><meta charset="utf-8"><title>phone probe</title>
<style>body{margin:0}iframe{border:0;width:${PHONE_WIDTH}px;height:4000px;display:block}</style>
</head><body><iframe id="report" src="file://$REPORT"></iframe>
<script>
document.getElementById("report").addEventListener("load", function () {
  var out = document.createElement("pre");
  try {
    var doc = this.contentDocument, root = doc.documentElement;
    var verdict = doc.getElementById("verdict").getBoundingClientRect();
    out.textContent = "probe: inner_width=" + this.contentWindow.innerWidth + " scroll_width=" +
      root.scrollWidth + " client_width=" + root.clientWidth + " verdict_left=" +
      Math.round(verdict.left) + " verdict_right=" + Math.round(verdict.right);
  } catch (e) { out.textContent = "probe-error: " + e; }
  document.body.appendChild(out);
});
</script></body></html>
EOF
rm -f "$PHONE_PNG"
PHONE_DOM="$WORK/report.phone.dom.html"
if EXTRA_FLAGS=--allow-file-access-from-files WINDOW_WIDTH=500 WINDOW_HEIGHT=4000 \
  render "$PROBE" "$PHONE_PNG" "$PHONE_DOM" "$WORK/report.phone.chromium.log"; then
  probe="$(grep -o 'probe: inner_width=[0-9]* scroll_width=[0-9]* client_width=[0-9]* verdict_left=-\{0,1\}[0-9]* verdict_right=-\{0,1\}[0-9]*' "$PHONE_DOM" | head -n 1)"
  if [ -z "$probe" ]; then
    fail "phone width: the layout probe wrote nothing: $(grep -o 'probe-error[^<]*' "$PHONE_DOM")"
  else
    read -r iw sw cw vl vr <<<"$(sed 's/probe: //; s/[a-z_]*=//g' <<<"$probe")"
    if [ "$iw" -ne "$PHONE_WIDTH" ]; then
      fail "phone width: the report's viewport is $iw px, not $PHONE_WIDTH ($probe)"
    elif [ "$sw" -le "$cw" ] && [ "$vl" -ge 0 ] && [ "$vr" -le "$cw" ]; then
      ok "phone width $PHONE_WIDTH px: no sideways scroll, the verdict fits ($probe)"
    else
      fail "phone width $PHONE_WIDTH px: the page overflows the window ($probe)"
    fi
  fi
  [ -s "$PHONE_PNG" ] && ok "phone screenshot $PHONE_PNG (the report in the left $PHONE_WIDTH px)"
else
  fail "chromium exited with an error on the phone-width probe"
fi

echo "report: $REPORT"
echo "screenshot: $PNG"
if [ "$FAILURES" -ne 0 ]; then
  echo "$FAILURES check(s) failed"
  exit 1
fi
echo "PASSED"
