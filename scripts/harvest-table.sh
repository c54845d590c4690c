#!/usr/bin/env bash
# Prints the daylight-harvesting day of a firmware run as the markdown table of
# docs/embedded.md ("A daylight-harvesting controller"): the `harvest` records that the
# firmware example prints with a basis that carries daylight
# (examples/firmware/src/harvest.rs), hour by hour, for the model's controller and for the
# conventional one commissioned at night.
#
# Usage: scripts/harvest-table.sh OUTPUT
#   OUTPUT  what the firmware printed, as scripts/firmware.sh BASIS OUTPUT writes it
#
# Exits 1 when OUTPUT holds no harvest records (a basis without daylight).
set -euo pipefail

if [[ $# -ne 1 ]]; then
    echo "usage: $0 OUTPUT" >&2
    exit 2
fi
out="$1"
if ! grep -q '^harvest step ' "$out"; then
    echo "harvest-table.sh: no harvest records in $out (does the basis carry daylight?)" >&2
    exit 1
fi

awk '
    # Value of key k in the current record (`... key value ...`).
    function field(k,    i) {
        for (i = 1; i < NF; i++) if ($i == k) return $(i + 1)
        return ""
    }
    function percent(e) { return sprintf("%+.1f %%", 100 * e) }
    $1 != "harvest" { next }
    $2 == "setup" {
        printf "Day %s, CIE standard general sky type %s, work-plane target %g lux.\n\n",
            field("date"), field("cie"), field("target")
    }
    $2 == "night" {
        printf "Commissioning at night (every luminaire at 1): sensor %.1f lux, work plane %.1f lux, ratio %.4f, set point %.1f lux.\n\n",
            field("sensor"), field("zone"), field("ratio"), field("setpoint")
        print "| local time | sun altitude (°) | diffuse horizontal (lux) | daylight at the sensor (lux) | daylight on the work plane (lux) | model: levels | model: power (W) | model: work plane (lux) | model: error | night-calibrated: level | night-calibrated: power (W) | night-calibrated: work plane (lux) | night-calibrated: error |"
        print "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    }
    $2 == "step" {
        time = substr(field("time"), 12, 5)
        step = sprintf("| %s | %.1f | %.0f | %.1f | %.1f", time, field("altitude"),
            field("diffuse_horizontal"), field("sensor_daylight"), field("zone_daylight"))
    }
    $2 == "model" {
        levels = ""
        for (i = 1; i < NF && $i != "levels"; i++) {}
        for (i++; i < NF && $i != "power"; i++) levels = levels (levels == "" ? "" : ", ") sprintf("%.2f", $i)
        model = sprintf(" | %s | %.1f | %.1f | %s", levels, field("power"), field("work_plane"),
            percent(field("error")))
    }
    $2 == "closed" {
        printf "%s%s | %.3f | %.1f | %.1f | %s |\n", step, model, field("level"), field("power"),
            field("work_plane"), percent(field("error"))
    }
' "$out"
