#!/usr/bin/env bash
# Reproduces the paper's Fig. 5, Fig. 6, Fig. 7 and Table 1, and on 3D inputs (a mesh and a
# volume, tools/make_scene_examples.cpp) its Fig. 3 and Fig. 8, with geolens and writes
# docs/reproduction.md and its pictures docs/reproduction/*.jpg (every figure and number on that
# page comes from this run):
#
#   bash scripts/reproduce_figures.sh
#
# It builds the CLI and the input generator (tools/make_figure_inputs.cpp) in $BUILD (default
# build, configured already, e.g. by scripts/setup.sh), draws the synthetic inputs (grid, graph,
# text; the map is examples/demo.png) into a temporary folder, runs `geolens magnify` and
# `geolens compare` on them, and composes the page from their JSON and Markdown reports. Takes
# under a minute on 2 cores. Exits non-zero if any run fails.
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD=${BUILD:-build}
cmake --build "$BUILD" --target geolens_cli make_figure_inputs make_scene_examples \
  -j"$(bash scripts/jobs.sh)" >/dev/null
GEOLENS=$BUILD/geolens
OUT=docs/reproduction
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$OUT" "$TMP/inputs"
"$BUILD/make_figure_inputs" "$TMP/inputs"
cp examples/demo.png "$TMP/inputs/map.png"
CONVERGED=(--tolerance 1e-7 --max-iterations 5000)
# The paper's figures are made with the paper's lift; the focus lens (the default) has its own
# section at the end.
PAPER=(--model lift)

# Fig. 5: a graph, a map and a page of text, each 1024 px shown at 360 px: the context is
# minified 2.8x, the focus (zoom 2.5) shown near full resolution.
fig5() {  # name, lens
  "$GEOLENS" magnify "$TMP/inputs/$1.png" -o "$TMP/fig5_$1.png" --lens "$2" --size 360x360 \
    --stats "$TMP/fig5_$1.json" --before-after "$OUT/fig5_$1.jpg" "${PAPER[@]}" \
    2>>"$TMP/warnings.txt"
}
fig5 graph circle:505,225,110:2.5
fig5 map circle:430,470,150:2.5
fig5 text circle:520,430,130:2.5

# Fig. 6: the metric spectrum on the grid, every lens calibrated to zoom 2. Each setting runs
# magnify (picture, iterations) and compare (region figures and Eq. 7 of the geometric lens).
fig6() {  # id, picture (yes/no), options...
  local id=$1 picture=$2
  shift 2
  local picture_args=()
  [[ $picture == yes ]] && picture_args=(--size 240x240)
  "$GEOLENS" magnify "$TMP/inputs/grid.png" -o "$TMP/fig6_$id.jpg" --lens circle:256,256,150:2 \
    "${picture_args[@]}" --stats "$TMP/fig6_$id.json" "${PAPER[@]}" "$@" 2>>"$TMP/warnings.txt"
  [[ $picture == yes ]] && cp "$TMP/fig6_$id.jpg" "$OUT/fig6_$id.jpg"
  "$GEOLENS" compare "$TMP/inputs/grid.png" -o "$TMP/fig6_$id" --lens circle:256,256,150:2 \
    --baseline-mesh 60 --format jpg --tile 64 "${PAPER[@]}" "$@" 2>>"$TMP/warnings.txt"
}
for alpha in 0 0.01 0.1 0.5; do
  fig6 "paper_$alpha" yes --metric paper --alpha "$alpha"
  fig6 "paperconv_$alpha" no --metric paper --alpha "$alpha" "${CONVERGED[@]}"
done
for alpha in 0 0.25 0.5 0.75 1; do
  fig6 "spectrum_$alpha" yes --metric spectrum --alpha "$alpha" "${CONVERGED[@]}"
done

# Fig. 7 and Table 1: every method at the same zoom and radius.
compare() {  # id, input, lens, options...
  local id=$1 input=$2 lens=$3
  shift 3
  "$GEOLENS" compare "$TMP/inputs/$input.png" -o "$TMP/cmp_$id" --lens "$lens" --format jpg \
    --tile 176 --jpeg-quality 75 "${PAPER[@]}" "$@" 2>>"$TMP/warnings.txt"
}
compare grid grid circle:256,256,150:2
compare grid_free grid circle:256,256,150:2 --boundary free
compare map2 map circle:512,512,150:2
compare map3 map circle:512,512,150:3
compare map2_sub map circle:512,512,150:2 --subdivide 2 --baseline-mesh 60
compare map2_mesa map circle:512,512,150:2 --profile mesa --baseline-mesh 60
compare map2_sphere map circle:512,512,150:2 --profile sphere --baseline-mesh 60
compare map2_paper map circle:512,512,150:2 --profile sphere --texture mvc --baseline-mesh 60
cp "$TMP/cmp_grid/panel.jpg" "$OUT/fig7_panel.jpg"
cp "$TMP/cmp_map2/panel.jpg" "$OUT/compare_demo_panel.jpg"

# The focus lens (the default) against the model it replaced (auto: the lift for circles, the
# field for shapes), on what a user points at: a line of text, a paragraph, a graph, a map.
printf '358 226\n624 226\n624 246\n358 246\n' >"$TMP/line.txt"
printf '358 318\n626 318\n626 492\n358 492\n' >"$TMP/paragraph.txt"
focus_case() {  # id, input, lens
  for model in focus auto; do
    "$GEOLENS" magnify "$TMP/inputs/$2.png" -o "$TMP/focus_$1_$model.png" --lens "$3" \
      --model "$model" --size 400x400 --stats "$TMP/focus_$1_$model.json" \
      --before-after "$TMP/focus_$1_${model}_ba.jpg" 2>>"$TMP/warnings.txt"
    cp "$TMP/focus_$1_${model}_ba.jpg" "$OUT/focus_$1_$model.jpg"
  done
}
focus_case line text "polygon:$TMP/line.txt:2"
focus_case paragraph text "polygon:$TMP/paragraph.txt:2"
focus_case graph graph circle:505,225,110:2
focus_case map map circle:512,512,120:2.5
# The trade-off: `compare --sweep` at zoom 2 and 3, a circle small enough that its largest
# footprint stays inside the image (grid 200 for the focus lens, 400 for the classic lenses).
"$GEOLENS" compare "$TMP/inputs/grid.png" -o "$TMP/sweep2" --lens circle:256,256,30:2 --sweep \
  --mesh 200 --baseline-mesh 400 2>>"$TMP/warnings.txt"
"$GEOLENS" compare "$TMP/inputs/grid.png" -o "$TMP/sweep3" --lens circle:256,256,20:3 --sweep \
  --mesh 200 --baseline-mesh 400 2>>"$TMP/warnings.txt"
cp "$TMP/sweep2/sweep.png" "$OUT/sweep_zoom2.png"
cp "$TMP/sweep3/sweep.png" "$OUT/sweep_zoom3.png"

# Fig. 3 and Fig. 8: 3D data rendered by geolens (a mesh, a volume) with a lens on the view: the
# Utah teapot with a polygon lens over its spout, a CT-like head phantom with a lens over its
# vessels and an aneurysm.
"$BUILD/make_scene_examples" "$TMP/scene" >/dev/null
TEAPOT_ARGS=(--view 30,15 --size 720x480 --lens polygon:examples/teapot_spout.txt:1.7)
PHANTOM_ARGS=(--transfer ct --view 20,35 --size 640x640 --lens circle:262,372,45:2.5)
printf '%s\n' "${TEAPOT_ARGS[*]}" "${PHANTOM_ARGS[*]}" >"$TMP/scene_args.txt"
scene() {  # id, input, options...
  local id=$1 input=$2
  shift 2
  "$GEOLENS" magnify "$TMP/scene/$input" -o "$TMP/$id.png" "$@" --stats "$TMP/$id.json" \
    --before-after "$OUT/$id.jpg" 2>>"$TMP/warnings.txt"
}
scene fig3_teapot teapot.obj "${TEAPOT_ARGS[@]}"
scene fig8_phantom phantom.nrrd "${PHANTOM_ARGS[@]}"

python3 - "$TMP" >"$TMP/reproduction.md" <<'EOF'
import json, re, sys

tmp = sys.argv[1]

def stats(name):
    return json.load(open(f"{tmp}/{name}.json"))

def report(folder):
    return {m["name"]: m for m in json.load(open(f"{tmp}/{folder}/report.json"))["methods"]}

def eq7(folder):
    text = open(f"{tmp}/{folder}/report.md").read()
    return float(re.search(r"Eq\. 7 energy[^:]*: ([0-9.]+) px\^2", text).group(1))

def f(x, digits=2):
    return "—" if x is None else f"{x:.{digits}f}"

def zone(m, z, key="mean"):
    return m["distortion"][z][key]

warnings = open(f"{tmp}/warnings.txt").read().strip().splitlines()
P = print

P("# Reproducing the paper's figures\n")
P("Generated by `bash scripts/reproduce_figures.sh` (under a minute): it draws the inputs with "
  "`tools/make_figure_inputs.cpp` (a grid, a graph and a page of text; the map is "
  "`examples/demo.png`), runs `geolens magnify` and `geolens compare`, and writes this page and "
  "the pictures in `docs/reproduction/`. Every number is measured by geolens's distortion "
  "analysis (`distortion.h`) with the definitions of `geolens compare`:\n")
P("- **zoom** = mean magnification sqrt(det J) over a small disk at the lens centre "
  "(`magnification_at`, radius max(grid cell, 0.05 r)); every lens is asked for the same zoom "
  "and every classic lens is matched to the zoom the geometric lens measured;")
P("- **shape distortion** = s1/s2 - 1 of each triangle's source -> screen Jacobian (0: shape "
  "kept), source-area weighted mean / max;")
P("- **regions** by source position: *focus* = within r / (2 zoom) of the centre (what a flat-top "
  "lens of the same radius shows at full zoom on the inner half of its disk), *transition* = the "
  "rest of the lens disk, *context* = outside;")
P("- **focus uniformity** = max / min magnification over the focus; **hidden** = source area not "
  "shown, percent of the image.\n")
P("The geometric lens runs with the CLI's defaults (gaussian profile, cotan texture weights, the "
  "paper's flattening weights, sliding border, the paper's 0.1 % stop, a 100 x 100 grid without "
  "adaptive subdivision) unless stated. The "
  "classic lenses are evaluated on a 200 x 200 grid with extra rings at r/2 and r "
  "(`classic_lens.h`).\n")

# ---------------------------------------------------------------------------------------------
P("## Fig. 5: a graph, a map and a page of text\n")
P("Each input is 1024 x 1024 and shown at 360 x 360, so the context is minified 2.8x while the "
  "focus (zoom 2.5) is shown at about full resolution: labels too small to read in the context "
  "become readable under the lens (the paper's \"multi-scale details are revealed\"). Input with "
  "the lens outlined on the left, output on the right.\n")
for name, what in [("graph", "node-link graph of \"company relations\""),
                   ("map", "city map (`examples/demo.png`)"),
                   ("text", "page of text")]:
    s = stats(f"fig5_{name}")
    lens = s["lenses"][0]
    P(f"![{name}](reproduction/fig5_{name}.jpg)\n")
    P(f"*{what}: lens r = {lens['radius']:.0f} px, zoom {lens['zoom_requested']:g} requested, "
      f"{lens['zoom_measured']:.2f} measured, {s['flipped']} flipped triangles, shape distortion "
      f"mean {s['distortion']['conformal_mean']:.3f}, max {s['distortion']['conformal_max']:.2f}.*\n")

# ---------------------------------------------------------------------------------------------
P("## Fig. 6: the alpha spectrum\n")
P("The paper blends the rigid and the stretched metric with alpha (Eq. 6) and shows the lens for "
  "alpha = 0, 0.01, 0.1, 0.5 after its 0.1 % stop. geolens implements that (`--metric paper`) and a "
  "spectrum that keeps its effect at convergence (`--metric spectrum`: target b R with "
  "b = (1 - alpha) + alpha (s1 + s2)/2, rigid at 0, the closest similarity at 1). Grid 512 x 512, "
  "lens r = 150 px, zoom 2 requested; geolens calibrates the bump height for every setting, so "
  "the settings are compared at equal zoom, not at equal height.\n")
row1 = [f"![paper {a}](reproduction/fig6_paper_{a}.jpg)" for a in ["0", "0.01", "0.1", "0.5"]]
P("| paper alpha 0 | 0.01 | 0.1 | 0.5 |\n|---|---|---|---|\n| " + " | ".join(row1) + " |\n")
spec = ["0", "0.25", "0.5", "0.75", "1"]
row2 = [f"![spectrum {a}](reproduction/fig6_spectrum_{a}.jpg)" for a in spec]
P("| spectrum alpha 0 | 0.25 | 0.5 | 0.75 | 1 |\n|---|---|---|---|---|\n| " + " | ".join(row2) +
  " |\n")
P("| metric | alpha | stop | iterations | zoom | h0 / r | focus | transition | context | max "
  "| Eq. 7 energy (px^2) | flipped |")
P("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
fig6_rows = ([("paper", a, "0.1 %", f"paper_{a}") for a in ["0", "0.01", "0.1", "0.5"]] +
             [("paper", a, "converged", f"paperconv_{a}") for a in ["0", "0.01", "0.1", "0.5"]] +
             [("spectrum", a, "converged", f"spectrum_{a}") for a in spec])
fig6 = {}
for metric, alpha, stop, id in fig6_rows:
    s = stats(f"fig6_{id}")
    g = report(f"fig6_{id}")["geometric"]
    fig6[id] = (s, g, eq7(f"fig6_{id}"))
    lens = s["lenses"][0]
    P(f"| {metric} | {alpha} | {stop} | {s['iterations']}{'' if s['converged'] else ' (cap)'} "
      f"| {g['zoom_center']:.3f} | {lens['height'] / 150:.3f} | {f(zone(g, 'focus'), 3)} "
      f"| {f(zone(g, 'transition'), 3)} | {f(zone(g, 'context'), 3)} "
      f"| {f(zone(g, 'overall', 'max'), 3)} | {fig6[id][2]:.0f} | {s['flipped']} |")
P("\n*focus / transition / context: mean shape distortion; max: over the whole image.*\n")
paper_alphas = ["0", "0.01", "0.1", "0.5"]
early = [fig6[f"paper_{a}"][1]["distortion"]["overall"]["mean"] for a in paper_alphas]
conv = [fig6[f"paperconv_{a}"][1]["distortion"]["overall"]["mean"] for a in paper_alphas]
spread = lambda v: (max(v) - min(v)) / max(v) * 100
P("What it shows:\n")
collapse = spread(conv) < 0.1
P(f"- **The paper's alpha {'hardly matters' if spread(early) < 5 else 'matters'} at equal zoom.** "
  f"After the 0.1 % stop the four lenses take "
  f"{', '.join(str(fig6[f'paper_{a}'][0]['iterations']) for a in paper_alphas)} iterations and "
  f"their mean shape distortion differs by {spread(early):.1f} %; converged, by "
  f"{spread(conv):.2f} %. " +
  ("The blend is a damped rigid (ARAP) step with the same fixed point for every alpha < 1 "
   "(docs/design.md), so whatever differences the paper's Fig. 6 shows come from stopping early "
   "at a fixed height; they are not a lever a user can rely on." if collapse else
   "The converged results differ, against the analysis in docs/design.md: worth a look."))
sp = {a: fig6[f"spectrum_{a}"] for a in spec}
def trend(values):
    if all(b > a for a, b in zip(values, values[1:])):
        return "rises"
    if all(b < a for a, b in zip(values, values[1:])):
        return "falls"
    return "is not monotone"
usable = [a for a in spec if abs(sp[a][1]["zoom_center"] / 2 - 1) <= 0.1 and sp[a][0]["flipped"] == 0
          and zone(sp[a][1], "overall", "max") < 10]
heights = [sp[a][0]["lenses"][0]["height"] / 150 for a in spec]
focus_means = [zone(sp[a][1], "focus") for a in spec]
maxima = [zone(sp[a][1], "overall", "max") for a in spec]
energies = [sp[a][2] for a in spec]
listed = lambda values, fmt: ", ".join(fmt.format(v) for v in values)
P(f"- **The spectrum** (converged): as alpha goes {', '.join(spec)}, the calibrated height h0/r "
  f"{trend(heights)} ({listed(heights, '{:.2f}')}), the mean shape distortion in the focus "
  f"{trend(focus_means)} ({listed(focus_means, '{:.3f}')}), the maximum {trend(maxima)} "
  f"({listed(maxima, '{:.3g}')}) and the Eq. 7 energy (distortion from rigid) {trend(energies)}. "
  f"Usable (zoom within 10 %, no flip, maximum below 10) for alpha = {', '.join(usable)}.\n")

# ---------------------------------------------------------------------------------------------
P("## Fig. 7: distortion heatmaps, ours next to the classic lenses\n")
P("The paper colours the shape distortion of its mesh next to Carpendale's poly-focal lens, blue "
  "(0) to red (the maximum, 0.45 in its result). Here: the same 512 x 512 grid and lens (r = 150 "
  "px, zoom 2), the geometric lens next to the six classic lenses, each matched to the zoom the "
  "geometric lens measured; one colour scale for all (red = the largest value of any method). The "
  "flat-top lenses with drop-off are the sigma-lens / Carpendale family the poly-focal lens belongs "
  "to.\n")
P("![Fig. 7 panel](reproduction/fig7_panel.jpg)\n")

def method_table(r, names=None):
    P("| method | zoom | focus uniformity | focus mean / max | transition mean / max "
      "| context mean / max | hidden % | flipped |")
    P("|---|---:|---:|---:|---:|---:|---:|---:|")
    for name, m in r.items():
        if names and name not in names:
            continue
        cells = [f"{f(zone(m, z), 3)} / {f(zone(m, z, 'max'), 3)}"
                 for z in ["focus", "transition", "context"]]
        P(f"| {name} | {m['zoom_center']:.3f} | {f(m['focus_uniformity'], 3)} | " +
          " | ".join(cells) + f" | {m['occluded_percent']:.2f} | {m['flipped']} |")
    P("")

grid = report("cmp_grid")
method_table(grid)
free = report("cmp_grid_free")["geometric"]
P(f"With the paper's free boundary (`--boundary free`, the setting of its Fig. 7) the geometric "
  f"lens measures zoom {free['zoom_center']:.3f}, shape distortion max "
  f"{zone(free, 'overall', 'max'):.3f}, context mean {zone(free, 'context'):.3f}: the border "
  f"condition changes little.\n")
gmax = zone(grid["geometric"], "overall", "max")
relation = "close to" if abs(gmax / 0.45 - 1) < 0.25 else "above" if gmax > 0.45 else "below"
means = {z: zone(grid["geometric"], z) for z in ["focus", "transition", "context"]}
worst = max(means, key=means.get)
steep = [zone(grid[n], "overall", "max") for n in ["bifocal", "flattop_linear", "flattop_cosine"]]
P(f"The geometric lens's maximum ({gmax:.2f}) is {relation} the paper's 0.45. Its distortion is "
  f"highest on average in its {worst} (mean focus {means['focus']:.3f}, transition "
  f"{means['transition']:.3f}, context {means['context']:.3f}) and reaches into the context; "
  f"every classic lens leaves the context exactly undistorted and puts its distortion in the "
  f"transition ring (flat tops and bifocal up to {min(steep):.2f}-{max(steep):.2f}, the "
  f"Sarkar-Brown fisheye {zone(grid['fisheye'], 'overall', 'max'):.2f} at its rim, its analytic "
  f"d = zoom - 1 for the zoom it needed to match).\n")

# ---------------------------------------------------------------------------------------------
P("## Table 1, measured\n")
P("The paper's Table 1 ticks which properties zoom-in, fisheye, bifocal, perspective wall, "
  "poly-focal, cube deformation and its lens have. Below, the lenses geolens implements, measured "
  "on `examples/demo.png` (1024 x 1024, lens r = 150 px at the centre). Perspective wall and cube "
  "deformation are not implemented. The properties in the last columns follow from the formulas "
  "(`classic_lens.h`) and the code, not from a measurement.\n")
props = {
    "geometric": ("smooth transition (piecewise linear on its mesh)", "circle, polygon, mask (library)",
                  "no"),
    "zoom_in": ("jump at the rim", "circle", "yes"),
    "fisheye": ("C0, kink at the rim", "circle", "no"),
    "fisheye_smooth": ("C1 at the rim", "circle", "no"),
    "bifocal": ("C0, kinks at r/2 and r", "circle", "no"),
    "flattop_linear": ("C0, kinks at r/2 and r", "circle", "no"),
    "flattop_cosine": ("C1", "circle", "no"),
}
for zoom in [2, 3]:
    r = report(f"cmp_map{zoom}")
    P(f"**Zoom {zoom}** (requested of the geometric lens; classic lenses matched to its "
      f"{r['geometric']['zoom_center']:.3f}):\n")
    method_table(r)
P("Properties:\n")
P("| method | continuity | lens shapes | occludes |\n|---|---|---|---|")
for name, (c, s, o) in props.items():
    P(f"| {name} | {c} | {s} | {o} |")
P("")
P("The geometric lens with adaptive subdivision, with other bump profiles, and in the paper's "
  "own setting (hemisphere profile, mean value texture weights), zoom 2:\n")
P("| geometric lens | zoom | focus uniformity | focus mean / max | transition mean / max "
  "| context mean / max | flipped |")
P("|---|---:|---:|---:|---:|---:|---:|")
variants = [("gaussian, cotan texture (default)", "cmp_map2"),
            ("gaussian, cotan, subdivided (`--subdivide 2`)", "cmp_map2_sub"),
            ("mesa, cotan", "cmp_map2_mesa"),
            ("sphere, cotan", "cmp_map2_sphere"), ("sphere, mvc (the paper's)", "cmp_map2_paper")]
var = {}
for label, folder in variants:
    g = report(folder)["geometric"]
    var[folder] = g
    cells = [f"{f(zone(g, z), 3)} / {f(zone(g, z, 'max'), 3)}" for z in ["focus", "transition", "context"]]
    P(f"| {label} | {g['zoom_center']:.3f} | {f(g['focus_uniformity'], 3)} | " + " | ".join(cells) +
      f" | {g['flipped']} |")
P("")

# ---------------------------------------------------------------------------------------------
m2, m3 = report("cmp_map2"), report("cmp_map3")
continuous = ["fisheye", "fisheye_smooth", "bifocal", "flattop_linear", "flattop_cosine"]
def lowest_max(r):
    best = min(continuous, key=lambda n: zone(r[n], "overall", "max"))
    return best, zone(r[best], "overall", "max")
b2, v2 = lowest_max(m2)
b3, v3 = lowest_max(m3)
g2, g3 = m2["geometric"], m3["geometric"]
P("## Where the paper's claim holds, and where it does not\n")
P("The paper claims its lens preserves shape better than the fisheye, bifocal, poly-focal and "
  "other lenses at the same magnification. Measured:\n")
below = lambda r: [n for n in continuous if zone(r[n], "overall", "max") <= zone(r["geometric"], "overall", "max")]
beaten = sorted(set(below(m2)) | set(below(m3)))
verdict = ("holds" if not beaten else
           "does not hold" if len(beaten) == len(continuous) else "holds only in part")
steep = [zone(r[n], "overall", "max") for r in (m2, m3)
         for n in ["bifocal", "flattop_linear", "flattop_cosine"]]
P(f"- **Maximum shape distortion: {verdict}.** The geometric lens's worst triangle has s1/s2 - 1 "
  f"= {zone(g2, 'overall', 'max'):.2f} at zoom 2 and {zone(g3, 'overall', 'max'):.2f} at zoom 3 "
  f"({zone(var['cmp_map2_sub'], 'overall', 'max'):.2f} at zoom 2 with adaptive subdivision); "
  f"the C1 fisheye reaches {zone(m2['fisheye_smooth'], 'overall', 'max'):.2f} and "
  f"{zone(m3['fisheye_smooth'], 'overall', 'max'):.2f}, the Sarkar-Brown fisheye "
  f"{zone(m2['fisheye'], 'overall', 'max'):.2f} and {zone(m3['fisheye'], 'overall', 'max'):.2f}, "
  f"the flat tops and bifocal {min(steep):.1f} to {max(steep):.1f}" +
  (f"; at one zoom or both, {', '.join(beaten)} stay{'s' if len(beaten) == 1 else ''} below it"
   if beaten else "") +
  f". No fold, and unlike the zoom-in ({m2['zoom_in']['occluded_percent']:.1f} % of the image "
  f"hidden at zoom 2) nothing is hidden.")
flat_names = ["bifocal", "flattop_linear", "flattop_cosine"]
flat_tops = [m2[n]["focus_uniformity"] for n in flat_names]
focus_holds = g2["focus_uniformity"] < 1.05 and zone(g2, "focus") < zone(m2["fisheye"], "focus")
P(f"- **Focus: {'holds' if focus_holds else 'does not hold'}.** Its focus is neither uniform nor undistorted: magnification "
  f"varies {g2['focus_uniformity']:.2f}x across the focus at zoom 2 "
  f"({g3['focus_uniformity']:.2f}x at zoom 3); over the same circle the zoom-in's varies "
  f"{m2['zoom_in']['focus_uniformity']:.2f}x and the bifocal's and the flat tops' "
  f"{min(flat_tops):.2f}x to {max(flat_tops):.2f}x (uniform within their flat tops, which span "
  f"part of the circle), and the mean shape distortion there is {zone(g2, 'focus'):.2f} against "
  f"{max(zone(m2[n], 'focus') for n in flat_names):.2f} for those and "
  f"{zone(m2['fisheye'], 'focus'):.2f} for the Sarkar-Brown fisheye. The gaussian bump is peaked "
  f"(fisheye-like); with adaptive subdivision its focus measures "
  f"{zone(var['cmp_map2_sub'], 'focus'):.2f} / {zone(var['cmp_map2_sub'], 'focus', 'max'):.2f} "
  f"(mean / max, against {zone(g2, 'focus'):.2f} / {zone(g2, 'focus', 'max'):.2f} without); the "
  f"flatter mesa and sphere profiles buy a more uniform focus at the price of "
  f"far more distortion in the transition and the context (the variants table above).")
P(f"- **Context: does not hold.** Every classic lens leaves everything outside its radius exactly "
  f"undistorted; the geometric lens spreads distortion over the whole image (context mean "
  f"{zone(g2, 'context'):.3f}, max {zone(g2, 'context', 'max'):.2f} at zoom 2) and compresses the "
  f"context slightly to make room. That is the paper's design (the distortion is spread thin "
  f"instead of concentrated), and it is small for the gaussian profile, but it is not \"shape "
  f"preserved\" where the classic lenses preserve it exactly.")
ps = var["cmp_map2_paper"]
classic_max = max(zone(r[n], "overall", "max") for r in (m2,) for n in continuous)
flatter = "flatter" if ps["focus_uniformity"] < g2["focus_uniformity"] else "no flatter"
worse = zone(ps, "overall", "max") > classic_max
P(f"- **The paper's own setting** (hemisphere profile, mean value texture weights): the focus is "
  f"{flatter} (uniformity {ps['focus_uniformity']:.2f}, mean shape distortion "
  f"{zone(ps, 'focus'):.3f}) but the walls of the bump distort the transition and the context: "
  f"max {zone(ps, 'transition', 'max'):.1f} in the transition and "
  f"{zone(ps, 'context', 'max'):.1f} in the context, "
  f"{'above' if worse else 'below'} every continuous classic lens's maximum "
  f"({classic_max:.1f}) and {zone(ps, 'context'):.3f} on average in the context where the classic "
  f"lenses have 0.")
P(f"- **Fig. 6's metric blend** {'is no lever at convergence' if collapse else 'changes the converged result'} "
  f"(above); the converging spectrum is usable for alpha = {', '.join(usable)}.\n")
# ---------------------------------------------------------------------------------------------
P("## The focus lens: the region given, magnified\n")
P("The default lens model since issue 13 (`--model focus`, `focus_lens.h`, docs/design.md): the "
  "region the user gives is magnified as a whole by its zoom, a similarity; the context gives way "
  "within a footprint (the region scaled by `--footprint`, default 2 x zoom, about its centre) "
  "along a power-law ring whose shape distortion is bounded, and nothing beyond the footprint "
  "moves. Below, each input with the lens outlined and the output (400 px), the focus model next "
  "to the model it replaced (`--model auto`: the paper's lift for circles, the field for "
  "shapes). *focus*: over the region given, mean magnification, max / min magnification "
  "(uniformity) and max shape distortion; *moved*: the largest displacement beyond the "
  "footprint.\n")
P("| case | model | focus zoom | uniformity | focus shape max | overall shape max | moved (px) | "
  "flipped |\n|---|---|---:|---:|---:|---:|---:|---:|")
for case, what in [("line", "a line of text (16:1 polygon), zoom 2"),
                   ("paragraph", "a paragraph (polygon), zoom 2"),
                   ("graph", "a graph (circle r = 110 px), zoom 2"),
                   ("map", "a map (circle r = 120 px), zoom 2.5")]:
    for model in ["focus", "auto"]:
        s = stats(f"focus_{case}_{model}")
        l = s["lenses"][0]
        P(f"| {what} | {s['model']} | {l['focus']['zoom']:.2f} | {l['focus']['uniformity']:.2f} "
          f"| {l['focus']['shape_max']:.2f} | {s['distortion']['conformal_max']:.2f} "
          f"| {l['displacement_beyond_footprint']:.1f} | {s['flipped']} |")
P("")
for case in ["line", "paragraph", "graph", "map"]:
    P(f"| focus ({case}) | auto ({case}) |\n|---|---|\n"
      f"| ![focus](reproduction/focus_{case}_focus.jpg) | ![auto](reproduction/focus_{case}_auto.jpg) |\n")

P("### The trade-off against the best possible radial lens\n")
P("A radial lens that magnifies a disk of radius r_f uniformly by M and leaves everything beyond "
  "R = F r_f in place has a shape distortion of at least 1 / (1 - ln M / ln F) - 1 somewhere "
  "(`radial_distortion_bound`); the classic lens `power_ring` reaches it. `geolens compare "
  "--sweep` solves one lens at footprint ratios F from zoom + 1 to 4 x zoom and every classic "
  "lens with radius F r_f and a flat top of the region's size, matched to the zoom reached. Grid "
  "512 x 512, a circle of r_f = 30 px (zoom 2) and 20 px (zoom 3) at the centre, so that every "
  "footprint stays inside the image; largest shape distortion, the focus uniformity in brackets "
  "where it is above 1.01; in the plots a filled point has a uniform focus, a hollow one not, and "
  "the dashed line is the bound.\n")
within, within_rim = [], []
for zoom in [2, 3]:
    text = open(f"{tmp}/sweep{zoom}/sweep.md").read()
    P(f"**Zoom {zoom}**\n")
    P(text[text.index("| F |"):])
    P(f"![sweep at zoom {zoom}](reproduction/sweep_zoom{zoom}.png)\n")
    for p in json.load(open(f"{tmp}/sweep{zoom}/sweep.json"))["points"]:
        if p["method"] == "geometric":
            within.append(p["shape_max"] / p["bound"])
            within_rim.append(p["shape_max"] / p["rim_bound"])
P(f"The focus lens is {min(within):.2f} to {max(within):.2f} times the radial bound and "
  f"{min(within_rim):.2f} to {max(within_rim):.2f} times its ring's (the rim bound; the issue "
  "asks for at most 1.3 times the radial bound). Its ring is the power ring with a rim that ends "
  "without a crease (the radial scale reaches 1 at the footprint's edge, docs/design.md), which "
  "compresses up to 1.15 times more within, on a 200 x 200 grid with vertices on the focus "
  "circle and the footprint's edge, refined where a triangle's slope is off by 7.5 % next to the "
  "focus circle; what it adds is the piecewise-linear mesh (its largest distortion sits in the "
  "triangles next to the focus circle, where the ring bends most) and, where the ring is not "
  "feasible, the 10 % slack of its anisotropy bound. The flat tops and the "
  "bifocal, of the same focus and footprint, distort more at every footprint; the fisheyes less, "
  "with foci that are not uniform; the zoom-in distorts nothing and hides a ring.\n")

# ---------------------------------------------------------------------------------------------
P("## Fig. 3 and Fig. 8: 3D data through the lens\n")
P("The paper puts its lens on renderings of 3D data: a teapot with a lens of arbitrary shape "
  "over the spout (Fig. 3) and a volume-rendered colon (Fig. 8). geolens renders a mesh (OBJ, "
  "PLY) or a volume (NIfTI, NRRD) itself, on the CPU (`render3d/`), tile by tile at the level "
  "of detail each part of the output is shown at: level 0 has 4 texels per frame pixel, so a "
  "focus magnified up to 4x is drawn from a render at its zoom, not from an enlarged picture. "
  "The inputs come from `tools/make_scene_examples.cpp`: the Utah teapot tessellated from "
  "Newell's 32 Bezier patches (69,432 triangles) and a 160^3 CT-like head phantom (int16, "
  "Hounsfield-like units: a skull with its upper front quarter cut away, a tree of "
  "contrast-filled vessels thinning to about one voxel with an aneurysm, a tumour with calcified "
  "specks, two ventricles). The runs, from the repository's root:\n")
scene_args = open(f"{tmp}/scene_args.txt").read().splitlines()
P("    build/make_scene_examples out/scene")
for (name, input_file), args in zip([("fig3_teapot", "teapot.obj"),
                                     ("fig8_phantom", "phantom.nrrd")], scene_args):
    P(f"    build/geolens magnify out/scene/{input_file} {args} -o out/{name}.png \\\n"
      f"      --before-after out/{name}.jpg --stats out/{name}.json")
P("")
P("Input with the lens outlined on the left, output on the right. *zoom*: the focus's mean "
  "magnification (over the region given; max / min: its uniformity); *shape distortion*: "
  "s1/s2 - 1 over the output's triangles; *tiles*: the source's tiles rendered for the output "
  "and the sum of their rendering times (tiles render on 2 threads at once); *render*: the wall-clock time "
  "of drawing the output and the before picture; *total*: the whole run.\n")
for name, what in [("fig3_teapot", "Fig. 3: the Utah teapot, a polygon lens over the spout"),
                   ("fig8_phantom", "Fig. 8: the head phantom (`--transfer ct`), a lens over "
                    "the vessels and the aneurysm")]:
    s = stats(name)
    l, src, t = s["lenses"][0], s["source"], s["timings_ms"]
    P(f"![{name}](reproduction/{name}.jpg)\n")
    P(f"*{what}: zoom {l['zoom_requested']:g} requested, {l['focus']['zoom']:.2f} measured "
      f"(max / min {l['focus']['uniformity']:.2f}), {s['flipped']} flipped triangles, shape "
      f"distortion mean {s['distortion']['conformal_mean']:.2f}, max "
      f"{s['distortion']['conformal_max']:.1f}; {src['tiles_rendered']:.0f} tiles "
      f"({src['frame'][0]} x {src['frame'][1]} frame, {src['scale']:g} texels per frame pixel "
      f"at level 0) in {src['tile_render_seconds']:.2f} s; render {t['render'] / 1000:.2f} s, "
      f"total {t['total'] / 1000:.2f} s on 2 cores.*\n")
P("What they show: the spout is shown 1.7x as a whole (asked for zoom 2, geolens warns that the "
  "lens does not fit there and solves at 1.72), and the pot gives way within the footprint: the "
  "body's right side is pressed towards the handle, its bottom bulges and the lid tilts, while "
  "the handle stays where it was. In the phantom the aneurysm and the vessels around it are shown 2.5x, drawn "
  "from renders at that zoom (vessels about a voxel thin stay continuous lines); the footprint "
  "(5 x the lens's radius) takes in most of the head, so the skull's outline grows too and the "
  "tumour moves to the upper right, still recognisable. The phantom's edges are blurred as a "
  "scanner's are (a Gaussian of 0.8 voxel): with hard one-voxel edges the gradient shading shows "
  "the voxel grid as rings on smooth surfaces, which is in the data, not the sampling (a "
  "per-ray jitter of the first sample leaves them).\n")

if warnings:
    P("Warnings printed by the runs:\n")
    for w in sorted(set(warnings)):
        P(f"    {w} ({warnings.count(w)} runs)")
EOF
mv "$TMP/reproduction.md" docs/reproduction.md
du -ch "$OUT"/*.jpg | tail -1
echo "wrote docs/reproduction.md and $OUT/*.jpg"
