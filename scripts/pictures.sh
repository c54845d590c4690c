#!/usr/bin/env bash
# Regenerates the pictures of docs/pictures/ (shown in docs/pictures.md and the README) with
# `eigenrad render`, from the example office:
#
#   office-plan.png       the work plane's plan, every channel at level 1, exact solve
#   office-surfaces.png   the surfaces' illuminance, the same solve
#   office-luminance.png  the surfaces' luminance (cd/m²), the same solve
#   office-dimmed.png     the work plane's plan through a basis (what the controller reads),
#                         luminaire lum1 at DALI arc 200, the others at 170, the window at 0.3
#   daylight-overcast.png the daylight office's work plane under the CIE overcast sky of
#                         10 000 lux at noon on the March equinox, luminaires off (exact solve):
#                         lux per 10 000 lux outside, i.e. the daylight factor in ‰
#   daylight-sun.png      the same under the CIE clear sky (type 12) with the sun: 15 000 lux
#                         diffuse, 70 000 lux direct normal
#   daylight-surfaces.png the daylight office's surfaces under that clear sky, exact solve
#   daylight-surfaces-basis.png
#                         the same from its basis (32 modes) through the runtime: the first
#                         reflection stored in the basis, the rest through the modes
#   l-office-plan.png     the L-shaped office's work plane (examples/l-office), both channels
#                         at level 1, no daylight (exact solve): the plan of the L, its walls,
#                         windows, columns, desk and sensors
#   office-year-power.png the daylight office in Greensboro (examples/office-year) over the
#                         shipped weather year: its model controller's power hour by hour
#                         (`eigenrad simulate --heatmap`, docs/simulate.md)
#
# Usage: scripts/pictures.sh [SCENE]      (default examples/office/scene.toml)
#
# Environment:
#   PICTURES_DIR   where the basis goes (default target/pictures)
#
# The form factors come from the form-factor cache when an earlier run left them (README,
# "The form-factor cache"). Progress goes to stderr.
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
# Paths as the pictures' captions name them: relative to the workspace.
cd "$root"
scene="${1:-examples/office/scene.toml}"
work="${PICTURES_DIR:-target/pictures}"
out="docs/pictures"

log() { printf '== %s\n' "$*" >&2; }

mkdir -p "$work" "$out"
log "building the eigenrad command (release)"
cargo build --release --quiet -p eigenrad-precompute --bin eigenrad >&2
# Where cargo put it: CARGO_TARGET_DIR when set (relative to the workspace), else target/.
target="${CARGO_TARGET_DIR:-target}"
[[ $target == /* ]] || target="$root/$target"
eigenrad="$target/release/eigenrad"

log "exact solve of $scene: plan and surfaces"
"$eigenrad" render "$scene" --plan "$out/office-plan.png" --surfaces "$out/office-surfaces.png"
"$eigenrad" render "$scene" --surfaces "$out/office-luminance.png" --quantity luminance

log "basis of $scene, evaluated through the runtime with dimmed channels"
"$eigenrad" build "$scene" -o "$work/office.basis" >"$work/office.report"
"$eigenrad" render "$scene" --basis "$work/office.basis" \
    --arc lum1=200 --arc lum2=170 --arc lum3=170 --arc lum4=170 --level window=0.3 \
    --plan "$out/office-dimmed.png"

daylit="examples/office-daylight/scene.toml"
off=(--level lum1=0 --level lum2=0 --level lum3=0 --level lum4=0)
log "exact solve of $daylit with daylight, luminaires off"
"$eigenrad" render "$daylit" "${off[@]}" --time 2026-03-20T12:00+01:00 \
    --cie overcast --dhi-lux 10000 --plan "$out/daylight-overcast.png"
"$eigenrad" render "$daylit" "${off[@]}" --time 2026-03-20T12:00+01:00 \
    --cie 12 --dhi-lux 15000 --dni-lux 70000 --plan "$out/daylight-sun.png"
"$eigenrad" render "$daylit" "${off[@]}" --time 2026-03-20T12:00+01:00 \
    --cie 12 --dhi-lux 15000 --dni-lux 70000 --surfaces "$out/daylight-surfaces.png"
log "basis of $daylit, its surfaces under daylight through the runtime"
"$eigenrad" build "$daylit" -o "$work/office-daylight.basis" >"$work/office-daylight.report"
"$eigenrad" render "$daylit" "${off[@]}" --basis "$work/office-daylight.basis" \
    --time 2026-03-20T12:00+01:00 --cie 12 --dhi-lux 15000 --dni-lux 70000 \
    --surfaces "$out/daylight-surfaces-basis.png"

l_office="examples/l-office/scene.toml"
log "exact solve of $l_office"
"$eigenrad" render "$l_office" --plan "$out/l-office-plan.png"

year="examples/office-year"
log "basis of $year/scene.toml, its controller's year in Greensboro"
"$eigenrad" build "$year/scene.toml" -o "$work/office-year.basis" >"$work/office-year.report"
"$eigenrad" simulate "$work/office-year.basis" --weather data/weather/greensboro-723170-tmy3.epw \
    --controller "$year/controller.toml" --heatmap "$out/office-year-power.png" >"$work/office-year.summary"

for f in office-plan office-surfaces office-luminance office-dimmed daylight-overcast daylight-sun \
    daylight-surfaces daylight-surfaces-basis l-office-plan office-year-power; do
    bytes=$(stat -c %s "$out/$f.png")
    log "$f.png: $bytes bytes"
    if ((bytes >= 200 * 1024)); then
        log "$f.png is larger than 200 KiB"
        exit 1
    fi
done
