#!/usr/bin/env bash
# Builds the firmware example (examples/firmware) with a given basis linked into flash, runs
# it under QEMU (mps2-an386, Cortex-M4F) and writes what it prints to a file. Prints the
# firmware's section sizes, with that basis and with the minimal tiny.basis, as lines:
#
#   size <label> basis_bytes <n> text <n> rodata <n> data <n> bss <n> flash <n>
#
# and the code-size probes' (examples/firmware/src/bin/code_size_*.rs), each less the empty
# skeleton's: `size runtime_<probe> text <n> rodata <n>` for channels, patches, levels and
# daylight, and `size sun_position text <n> rodata <n>` (the sun's position, without the
# runtime).
#
# Usage: scripts/firmware.sh BASIS OUTPUT
#   BASIS   a basis file (format in docs/format.md)
#   OUTPUT  where the firmware's standard output goes (the record format is described at the
#           top of examples/firmware/src/main.rs)
#
# Environment: FIRMWARE_TARGET_DIR (default target/firmware), FIRMWARE_TIMEOUT (seconds,
# default 300). Exits 77 when QEMU is missing and cannot be installed, so that callers can
# tell "could not run" from "ran and failed".
set -euo pipefail

if [[ $# -ne 2 ]]; then
    echo "usage: $0 BASIS OUTPUT" >&2
    exit 2
fi
root="$(cd "$(dirname "$0")/.." && pwd)"
basis="$(realpath "$1")"
output="$(realpath -m "$2")"
tiny="$root/runtime/tests/data/tiny.basis"
target_dir="${FIRMWARE_TARGET_DIR:-$root/target/firmware}"
timeout_s="${FIRMWARE_TIMEOUT:-300}"
triple=thumbv7em-none-eabihf

log() { printf '== %s\n' "$*" >&2; }

# Root or not, run a command with the rights apt needs.
as_root() {
    if [[ $(id -u) -eq 0 ]]; then
        "$@"
    elif command -v sudo >/dev/null; then
        sudo -n "$@"
    else
        return 1
    fi
}

if ! command -v qemu-system-arm >/dev/null; then
    log "installing qemu-system-arm"
    if ! { as_root apt-get update -qq && as_root apt-get install -y -qq qemu-system-arm; } >&2 \
        || ! command -v qemu-system-arm >/dev/null; then
        echo "firmware.sh: qemu-system-arm is not installed and could not be installed" >&2
        exit 77
    fi
fi

if ! rustup target list --installed | grep -qx "$triple"; then
    log "adding the $triple target"
    rustup target add "$triple" >&2
fi

# Builds the firmware with basis $1 in target folder $2 and copies the ELF to $3; further
# arguments go to cargo. The tiny build has a folder of its own: its fingerprint then stays
# fresh from one call to the next, and only the build with the caller's basis is redone.
build() {
    local basis="$1" dir="$2" elf="$3"
    shift 3
    log "building the firmware with $basis"
    (cd "$root/examples/firmware" &&
        EIGENRAD_BASIS="$basis" CARGO_TARGET_DIR="$dir" cargo build --release --quiet "$@") >&2
    cp "$dir/$triple/release/eigenrad-firmware" "$elf"
}

# A tool that prints section sizes in System V form (`name size addr` rows).
size_tool() {
    local t
    for t in llvm-size rust-size arm-none-eabi-size; do
        if command -v "$t" >/dev/null; then
            echo "$t"
            return
        fi
    done
    for t in "$HOME"/.rustup/toolchains/*/lib/rustlib/*/bin/llvm-size; do
        if [[ -x $t ]]; then
            echo "$t"
            return
        fi
    done
}

# Prints "name size" for every section of ELF $1.
sections() {
    local tool
    tool="$(size_tool)"
    if [[ -n $tool ]]; then
        "$tool" -A "$1" | awk 'NF >= 2 && $1 ~ /^\./ { print $1, $2 }'
    else
        # readelf -SW: "[Nr] Name Type Address Off Size ..." with sizes in hex.
        # Hex to decimal in the shell: not every awk has strtonum.
        readelf -SW "$1" | sed 's/^ *\[ *[0-9]*\]//' | awk '$1 ~ /^\./ { print $1, $5 }' |
            while read -r name hex; do echo "$name $((16#$hex))"; done
    fi
}

# Prints the size line for ELF $1, labelled $2, built with basis $3.
report_size() {
    sections "$1" | awk -v label="$2" -v bytes="$(stat -c %s "$3")" '
        { size[$1] = $2 }
        END {
            # Flash holds the vector table, code, constants and the initial values of .data.
            flash = size[".vector_table"] + size[".text"] + size[".rodata"] + size[".data"]
            printf "size %s basis_bytes %d text %d rodata %d data %d bss %d flash %d\n",
                label, bytes, size[".text"], size[".rodata"], size[".data"],
                size[".bss"] + size[".uninit"], flash
        }'
}

# Prints the code-size line of probe $1 (`.text` and `.rodata` less the empty probe's),
# labelled $2 (default runtime_$1).
report_probe() {
    local release="$target_dir/tiny/$triple/release"
    { sections "$release/code_size_$1" | sed 's/^/probe /'; sections "$release/code_size_empty"; } |
        awk -v label="${2:-runtime_$1}" '
            $1 == "probe" { probe[$2] = $3; next }
            { empty[$1] = $2 }
            END {
                printf "size %s text %d rodata %d\n", label,
                    probe[".text"] - empty[".text"], probe[".rodata"] - empty[".rodata"]
            }'
}

mkdir -p "$target_dir"
# The tiny build also builds the code-size probes (every binary of the example).
build "$tiny" "$target_dir/tiny" "$target_dir/firmware-tiny.elf" --bins
build "$basis" "$target_dir" "$target_dir/firmware.elf" --bin eigenrad-firmware

log "running under QEMU"
status=0
(cd "$root/examples/firmware" &&
    timeout "$timeout_s" qemu-system-arm -cpu cortex-m4 -machine mps2-an386 -nographic \
        -semihosting-config enable=on,target=native -icount shift=0 \
        -kernel "$target_dir/firmware.elf") >"$output" || status=$?

report_size "$target_dir/firmware-tiny.elf" tiny "$tiny"
report_size "$target_dir/firmware.elf" basis "$basis"
report_probe channels
report_probe patches
report_probe levels
report_probe daylight
report_probe sun sun_position

if [[ $status -ne 0 ]]; then
    echo "firmware.sh: the firmware failed (status $status); its output is in $output" >&2
    tail -n 5 "$output" >&2 || true
    exit 1
fi
