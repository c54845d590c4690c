#!/usr/bin/env bash
# Measures the firmware example (examples/firmware) on one scene for mode counts 16, 32, 64
# and storage f32, f16, i16 (9 bases), and prints the two markdown tables of docs/embedded.md
# (flash and RAM; instructions per call) and the runtime's own code.
#
# For each basis: `eigenrad build SCENE --modes P --precision S`, then scripts/firmware.sh
# (build for thumbv7em-none-eabihf with the basis in flash, run under QEMU mps2-an386 with
# -icount shift=0). The figures are what the firmware prints (see the top of
# examples/firmware/src/main.rs) and the section sizes firmware.sh reports, with the basis and
# with the 2-patch runtime/tests/data/tiny.basis.
#
# Usage: scripts/embedded-table.sh [SCENE]        (default examples/office/scene.toml)
#
# Environment:
#   EMBEDDED_TABLE_DIR    where bases, firmware output and builds go
#                         (default target/embedded-table)
#   EMBEDDED_TABLE_REUSE  1: keep bases already in that folder instead of rebuilding them
#                         (a build of the office takes about a minute of CPU)
#   EMBEDDED_TABLE_MODES  mode counts (default "16 32 64")
#   EMBEDDED_TABLE_STORAGE storage precisions (default "f32 f16 i16")
#   EIGENRAD_BIN          an eigenrad command to use instead of building one (release);
#                         the bases it writes are the same whatever its build profile
#
# Progress goes to stderr; the tables go to stdout.
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
scene="$(realpath "${1:-$root/examples/office/scene.toml}")"
dir="${EMBEDDED_TABLE_DIR:-$root/target/embedded-table}"
reuse="${EMBEDDED_TABLE_REUSE:-0}"
modes_list="${EMBEDDED_TABLE_MODES:-16 32 64}"
storage_list="${EMBEDDED_TABLE_STORAGE:-f32 f16 i16}"
# Flash of the part memory.x describes (bytes).
flash_limit=$((512 * 1024))

log() { printf '== %s\n' "$*" >&2; }

mkdir -p "$dir"
if [[ -n ${EIGENRAD_BIN:-} ]]; then
    eigenrad="$(realpath "$EIGENRAD_BIN")"
else
    log "building the eigenrad command (release)"
    (cd "$root" && cargo build --release --quiet -p eigenrad-precompute --bin eigenrad) >&2
    # Where cargo put it: CARGO_TARGET_DIR when set (relative to the workspace, where cargo
    # ran), else the workspace's target folder.
    target="${CARGO_TARGET_DIR:-target}"
    [[ $target == /* ]] || target="$root/$target"
    eigenrad="$target/release/eigenrad"
fi

# Value of field $2 in the first record of file $1 that starts with words $3...: records are
# `word word ... key value key value`.
field() {
    local file="$1" key="$2"
    shift 2
    awk -v key="$key" -v prefix="$*" '
        index($0, prefix " ") == 1 {
            for (i = 1; i < NF; i++) if ($i == key) { print $(i + 1); exit }
        }' "$file"
}

kib() { awk -v b="$1" 'BEGIN { printf "%.1f", b / 1024 }'; }

memory=()
instructions=()
for p in $modes_list; do
    for s in $storage_list; do
        name="p$p-$s"
        basis="$dir/$name.basis"
        if [[ $reuse != 1 || ! -s $basis ]]; then
            log "building $name from $scene"
            "$eigenrad" build "$scene" -o "$basis" --modes "$p" --precision "$s" \
                >"$dir/$name.report"
        fi
        bytes=$(stat -c %s "$basis")
        log "running the firmware with $name ($bytes bytes)"
        status=0
        FIRMWARE_TARGET_DIR="$dir/firmware" "$root/scripts/firmware.sh" "$basis" "$dir/$name.out" \
            >"$dir/$name.sizes" 2>"$dir/$name.log" || status=$?
        if [[ $status -ne 0 ]]; then
            # A basis too large for flash fails at link time (memory.x); say so in the row.
            reason="firmware failed, see $dir/$name.log"
            if grep -q "will not fit in region\|overflowed by" "$dir/$name.log"; then
                reason="does not link: flash overflows"
            fi
            log "$name: $reason"
            memory+=("$(printf '| %s | %s | %s | – | – | – | no (%s) | – | – | – |' \
                "$p" "$s" "$bytes" "$reason")")
            instructions+=("$(printf '| %s | %s | – | – | – | – | – | – | – | – | – |' "$p" "$s")")
            continue
        fi
        sizes="$dir/$name.sizes"
        last_sizes="$sizes"
        out="$dir/$name.out"
        text0=$(field "$sizes" text size tiny)
        text1=$(field "$sizes" text size basis)
        ro0=$(field "$sizes" rodata size tiny)
        ro1=$(field "$sizes" rodata size basis)
        flash=$(field "$sizes" flash size basis)
        fits=yes
        ((flash <= flash_limit)) || fits=no
        size_of=$(field "$out" size_of evaluator)
        ram=$(field "$out" ram_bytes evaluator)
        channel_size_of=$(field "$out" size_of channel_evaluator)
        channel_ram=$(field "$out" ram_bytes channel_evaluator)
        stack=$(field "$out" high_water stack)
        memory+=("$(printf '| %s | %s | %s | %s → %s | %s → %s | %s B (%s KiB) | %s | %s / %s | %s / %s | %s |' \
            "$p" "$s" "$bytes" "$text0" "$text1" "$ro0" "$ro1" "$flash" "$(kib "$flash")" "$fits" \
            "$channel_size_of" "$channel_ram" "$size_of" "$ram" "$stack")")
        row="| $p | $s |"
        for what in full_update channel_update read_outputs full_update_read_outputs \
            channel_update_read_outputs channel_exitance patch_update patch_read_outputs \
            patch_exitance; do
            n=$(awk -v what="$what" '$1 == "instructions" && $2 == what { print $3 }' "$out")
            row="$row ${n:-–} |"
        done
        instructions+=("$row")
    done
done

printf '### Flash and RAM\n\n'
printf '| p | storage | basis (bytes) | .text (tiny → with basis) | .rodata (tiny → with basis) | flash used | fits 512 KiB | ChannelEvaluator size_of / RAM_BYTES (bytes) | Evaluator size_of / RAM_BYTES (bytes) | stack high-water (bytes) |\n'
printf '|---|---|---|---|---|---|---|---|---|---|\n'
printf '%s\n' "${memory[@]}"
printf '\n### Instructions per call\n\n'
printf '| p | storage | full update | one channel | read all outputs | full update + read all outputs | one channel + read all outputs | one patch exitance | set one patch exitance | read all outputs, patch exitance set | one patch exitance, patch exitance set |\n'
printf '|---|---|---|---|---|---|---|---|---|---|---|\n'
printf '%s\n' "${instructions[@]}"

if [[ -n ${last_sizes:-} ]]; then
    printf "\n### The runtime's own code\n\n"
    printf '| what the firmware links | .text (bytes) | .rodata (bytes) |\n'
    printf '|---|---|---|\n'
    printf '| decoding + every `ChannelEvaluator` operation, grid figures included | %s | %s |\n' \
        "$(field "$last_sizes" text size runtime_channels)" \
        "$(field "$last_sizes" rodata size runtime_channels)"
    printf '| decoding + every `Evaluator` operation but the grids | %s | %s |\n' \
        "$(field "$last_sizes" text size runtime_patches)" \
        "$(field "$last_sizes" rodata size runtime_patches)"
    printf '| decoding + channel levels + outputs + `LevelProblem` (levels for a target) | %s | %s |\n' \
        "$(field "$last_sizes" text size runtime_levels)" \
        "$(field "$last_sizes" rodata size runtime_levels)"
fi
