#!/usr/bin/env bash
# Measures the lens options on examples/demo.png with one lens (circle:512,512,150:Z) and prints
# a Markdown table on stdout, one row per option combination, from the CLI's --stats JSON.
#
#   bash scripts/measure_options.sh > table.md
#
# Environment: GEOLENS (the CLI binary, default ./build/geolens), REPEATS (runs per row, default
# 3: the figures are taken from the first run and must be identical in every run, the total time
# is the median of the runs). Every output goes to a temporary directory that is removed at the
# end. A row whose lens misses its zoom (the CLI's stderr warning) is marked "missed"; a run that
# fails is shown as a FAILED row with its exit code, and the script exits with 1 after the table.
set -euo pipefail
cd "$(dirname "$0")/.."

GEOLENS=${GEOLENS:-./build/geolens}
REPEATS=${REPEATS:-3}
IMAGE=examples/demo.png
[[ -x $GEOLENS ]] || { echo "measure_options: no executable $GEOLENS" >&2; exit 2; }
[[ -f $IMAGE ]] || { echo "measure_options: no $IMAGE" >&2; exit 2; }

TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# One row: id, profile, texture, weights, label for the extra column, zoom, extra CLI arguments.
ROWS=()
add_row() { ROWS+=("$1|$2|$3|$4|$5|$6|$7"); }

n=0
for profile in gaussian sphere mesa; do
  for texture in cotan mvc; do
    for weights in paper cotan; do
      for zoom in 2 3 4; do
        add_row $((n++)) "$profile" "$texture" "$weights" "sliding" "$zoom" ""
      done
    done
  done
done
for zoom in 2 3; do
  for boundary in fixed free; do
    add_row $((n++)) gaussian cotan paper "$boundary" "$zoom" "--boundary $boundary"
  done
  add_row $((n++)) gaussian cotan paper "converged (tol 1e-7, max 2000)" "$zoom" \
    "--tolerance 1e-7 --max-iterations 2000"
  add_row $((n++)) gaussian cotan paper "mesh 200" "$zoom" "--mesh 200"
done

for row in "${ROWS[@]}"; do
  IFS='|' read -r id profile texture weights label zoom extra <<<"$row"
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$id" "$profile" "$texture" "$weights" "$label" "$zoom" \
    >"$TMP/row_$id.meta"
  for ((rep = 0; rep < REPEATS; rep++)); do
    base="$TMP/row_${id}_$rep"
    read -ra extra_args <<<"$extra"
    # The paper's lift: these options are its (the focus model, the default, takes none of them).
    cmd=("$GEOLENS" magnify "$IMAGE" -o "$base.png" --lens "circle:512,512,150:$zoom"
      --model lift --profile "$profile" --texture "$texture" --weights "$weights"
      "${extra_args[@]}" --stats "$base.json")
    echo "${cmd[*]}" >"$base.cmd"
    rc=0
    "${cmd[@]}" 2>"$base.err" >/dev/null || rc=$?
    echo "$rc" >"$base.rc"
    rm -f "$base.png"
    if ((rc != 0)); then break; fi
  done
  echo "measured row $id: $profile $texture $weights $label zoom $zoom" >&2
done

python3 - "$TMP" "${#ROWS[@]}" "$REPEATS" <<'EOF'
import json, os, statistics, sys

tmp, nrows, repeats = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
failed = False

def fmt(x, digits):
    return f"{x:.{digits}f}"

def figures(s):
    lens = s["lenses"][0]
    return (lens["zoom_measured"], lens["height"], s["flipped"], s["iterations"],
            s["converged"], s["calibration_solves"], s["distortion"]["conformal_mean"],
            s["distortion"]["conformal_max"])

print("| profile | texture | weights | boundary / extra | zoom requested | zoom measured | h0/r "
      "| flipped | iterations | calibration solves | conformal mean | conformal max | total ms |")
print("|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for i in range(nrows):
    meta = open(f"{tmp}/row_{i}.meta").read().rstrip("\n").split("\t")
    profile, texture, weights, label, zoom = meta[1:]
    head = f"| {profile} | {texture} | {weights} | {label} | {zoom} "
    runs, warnings = [], []
    for rep in range(repeats):
        base = f"{tmp}/row_{i}_{rep}"
        rc = int(open(base + ".rc").read())
        err = open(base + ".err").read().strip()
        if rc != 0:
            failed = True
            cmd = open(base + ".cmd").read().strip()
            print(head + f"| FAILED (exit {rc}: `{cmd}`: {err}) |  |  |  |  |  |  |  |")
            runs = None
            break
        runs.append(json.load(open(base + ".json")))
        warnings.append("warning" in err)
    if runs is None:
        continue
    first = figures(runs[0])
    if any(figures(r) != first for r in runs[1:]) or len(set(warnings)) != 1:
        print(f"measure_options: row {i} differs between runs", file=sys.stderr)
        failed = True
    zoom_m, height, flipped, iterations, converged, solves, cmean, cmax = first
    total = statistics.median(r["timings_ms"]["total"] for r in runs)
    zoom_cell = fmt(zoom_m, 3) + (" **missed**" if warnings[0] else "")
    flip_cell = f"**{flipped}**" if flipped else "0"
    iter_cell = str(iterations) + ("" if converged else " (cap)")
    print(head + f"| {zoom_cell} | {fmt(height / 150.0, 3)} | {flip_cell} | {iter_cell} "
          f"| {solves} | {fmt(cmean, 4)} | {fmt(cmax, 3)} | {fmt(total, 0)} |")
sys.exit(1 if failed else 0)
EOF
