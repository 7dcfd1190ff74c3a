#!/usr/bin/env bash
# Redraws the figures in docs/img/ with the commands the documents give
# beside them (each figure's document names its command), through the
# tools' --plot (matplotlib, tools/plot/tnvplot).
#   scripts/figures.sh [BUILD_DIR] [NAME_GLOB]
# BUILD_DIR defaults to build/release; NAME_GLOB (e.g. 'boring-*') redraws
# only the figures whose file name matches. The emulated node's saved
# parameters live in a fresh folder for the run (XDG_STATE_HOME), so a set
# saved on this machine does not change the figures. About 10 minutes on
# the shared two-core machine (the circles, the path and the soak most of it).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
only=${2:-*}
hil=$build/tools/tnv-hil
ctl=$build/tools/tnvctl
img=docs/img
for t in "$hil" "$ctl"; do [[ -x $t ]] || { echo "figures: $t not built" >&2; exit 1; }; done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export XDG_STATE_HOME=$work/state
mkdir -p "$XDG_STATE_HOME" "$work/tune"

wanted() { [[ $1 == $only ]]; }
draw() {  # NAME COMMAND...: runs the command when NAME matches, quietly unless it fails
  local name=$1
  shift
  wanted "$name" || return 0
  local t0=$SECONDS
  if ! "$@" >"$work/out.txt" 2>&1; then
    cat "$work/out.txt" >&2
    echo "figures: $name failed" >&2
    exit 1
  fi
  echo "figures: $name ($((SECONDS - t0)) s)"
}

# docs/reproduction-s1.md: the four circle figures.
if wanted 'circle-*'; then
  draw circle-figures "$hil" table3 --plot-dir "$work/s1"
  cp "$work/s1/circle-no-cut.svg" "$work/s1/circle-cut-900.svg" "$img/"
fi

# docs/input-shaping.md
draw shaper-sensitivity-zvd-30hz "$hil" shaper design --type zvd --freq-hz 30 --zeta 0.02 --plot "$img/shaper-sensitivity-zvd-30hz.svg"
draw shaper-two-mode-zv-30-100hz "$hil" shaper design --type zv --freq-hz 30 --freq2-hz 100 --zeta 0.02 --plot "$img/shaper-two-mode-zv-30-100hz.svg"
draw shaper-grid-methods "$hil" shaper grid --zeta 0 --plot "$img/shaper-grid-methods.svg"
draw shaper-move-flex30-zvd-20mm "$hil" shaper move --scenario flex-30 --axis x --distance-mm 20 --shaper zvd --seeds 5 --plot "$img/shaper-move-flex30-zvd-20mm.svg"
draw shaper-move-flex30-zvd-10mm "$hil" shaper move --scenario flex-30 --axis x --distance-mm 10 --shaper zvd --seeds 5 --plot "$img/shaper-move-flex30-zvd-10mm.svg"
if wanted shaper-jog-flex30; then
  # The jog session of docs/input-shaping.md ("Jogging through the shaper").
  sed -n "/^cat > jog.csv <<'EOF'$/,/^EOF$/p" docs/input-shaping.md | sed '1d;$d' > "$work/jog.csv"
  [[ -s $work/jog.csv ]] || { echo "figures: no jog.csv block in docs/input-shaping.md" >&2; exit 1; }
  draw shaper-jog-flex30 "$hil" shaper jog --scenario flex-30 --commands "$work/jog.csv" --path-accel 2000 --path-jerk 4e6 \
    --plot "$img/shaper-jog-flex30.svg"
fi

# docs/frequency-response.md
draw freq-response-x-open "$hil" freq-response --axis x --loop open --scenario tests/data/tables/no-friction.toml \
  --plot "$img/freq-response-x-open.svg"

# docs/motion.md
draw path-nas979-rdvsc "$hil" path tests/data/paths/nas979_diamond_circle_square.ngc --plot "$img/path-nas979-rdvsc.svg"

# docs/reproduction-s3.md
draw arsc-compare "$hil" arsc compare --plot "$img/arsc-compare.svg"
for c in 1 2 3 4; do
  for v in faithful robust; do
    draw "arsc-case$c-$v" "$hil" arsc run --poles "case$c" --variant "$v" --plot "$img/arsc-case$c-$v.svg"
  done
done
draw arsc-tick "$hil" arsc tick --plot "$img/arsc-tick.svg"
draw arsc-tick-arc "$hil" arsc tick --path arc --plot "$img/arsc-tick-arc.svg"

# docs/reproduction-s4.md
bore=(boring --parts 30 --change-at 11,21 --seeds 1000)
draw boring-sigma16-alpha05 "$hil" "${bore[@]}" --sigma-mm 0.016231 --alpha0 0.5 --plot "$img/boring-sigma16-alpha05.svg"
draw boring-sigma5-alpha1-normalised "$hil" "${bore[@]}" --sigma-mm 0.005 --alpha0 1.0 --plot "$img/boring-sigma5-alpha1-normalised.svg"
draw boring-sigma5-alpha1-printed "$hil" "${bore[@]}" --sigma-mm 0.005 --alpha0 1.0 --gain-form printed --plot "$img/boring-sigma5-alpha1-printed.svg"
draw boring-sigma5-alpha1-kalman "$hil" "${bore[@]}" --sigma-mm 0.005 --alpha0 1.0 --gain-form kalman --plot "$img/boring-sigma5-alpha1-kalman.svg"

# docs/autotune.md: best-circle-no-cut and best-circle-cut-1200 come from
# the reference run, best-circle-table-sticky from the sticky table's.
if wanted 'best-circle-*'; then
  draw best-circle-reference "$hil" best-circle --seeds 8 --plot-dir "$work/best"
  draw best-circle-sticky "$hil" best-circle --seeds 8 --scenario tests/data/tables/sticky.toml --plot-dir "$work/best-sticky"
  for f in best-circle-no-cut best-circle-cut-1200; do
    [[ ! -f $work/best/$f.svg ]] || cp "$work/best/$f.svg" "$img/"
  done
  [[ ! -f $work/best-sticky/best-circle-table-sticky.svg ]] || cp "$work/best-sticky/best-circle-table-sticky.svg" "$img/"
fi

# docs/safety.md
draw soak "$hil" soak --hours 1 --plot "$img/soak.svg"

# docs/tuning-guide.md: the bench session on the emulated node, in order.
if wanted 'tuning-*'; then
  t=$work/tune
  (cd "$work" && "$OLDPWD/$ctl" --emu capture --circle --csv tune/baseline.csv \
     --plot "$OLDPWD/$img/tuning-baseline.svg" --label "papers' defaults" \
     --title "tnvctl --emu capture --circle: the papers' defaults (no-cut, seed 0)") >"$work/out.txt" 2>&1 \
    || { cat "$work/out.txt" >&2; exit 1; }
  for g in 0 0.6; do
    printf 'params set y.sliding.gamma=%s\ncapture --circle --csv %s/gamma-%s.csv\n' "$g" "$t" "$g" | "$ctl" --emu script - >/dev/null 2>&1
  done
  printf 'params set y.sliding.gamma=0.304\n' | "$ctl" --emu script - >/dev/null 2>&1
  draw tuning-gamma "$ctl" plot --csv "$t/gamma-0.csv" --csv "$t/baseline.csv" --csv "$t/gamma-0.6.csv" \
    --label "y gamma 0" --label "y gamma 0.304 (papers')" --label "y gamma 0.6" \
    --title "y.sliding.gamma: no-cut circle, seed 0 (polar plot: 99.8% of R suppressed)" --out "$img/tuning-gamma.svg"
  for e in 0.2 0.4 0.8; do
    printf 'params set y.sliding.eta_mm_s=%s\ncapture --circle --csv %s/eta-%s.csv\n' "$e" "$t" "$e" | "$ctl" --emu script - >/dev/null 2>&1
  done
  draw tuning-eta "$ctl" plot --csv "$t/baseline.csv" --csv "$t/eta-0.2.csv" --csv "$t/eta-0.4.csv" --csv "$t/eta-0.8.csv" \
    --label "y eta 0.1014 (papers')" --label "y eta 0.2" --label "y eta 0.4" --label "y eta 0.8" \
    --title "y.sliding.eta_mm_s: no-cut circle, seed 0 (polar plot: 99.8% of R suppressed)" --out "$img/tuning-eta.svg"
  printf 'params set y.sliding.eta_mm_s=0.4\nenable\ncapture --channels pos_y,ref_y,command_y,s_y,d_hat_y --trigger immediate --run "move --axis y --distance-mm 2 --speed-mm-s 20" --tail-s 0.1 --csv %s/move-y.csv --plot %s --title "move y +2 mm at 20 mm/s with y eta 0.4 (capture --trigger immediate --tail-s 0.1)"\n' \
    "$t" "$img/tuning-move-y.svg" | "$ctl" --emu script - >"$work/out.txt" 2>&1 || { cat "$work/out.txt" >&2; exit 1; }
  echo "figures: tuning-baseline, tuning-move-y"
fi
# The figures' data files (.plot.json or .plot.csv, written beside each figure so it can
# be redrawn) are not kept in docs/.
rm -f "$img"/*.plot.json "$img"/*.plot.csv
echo "figures: done"
