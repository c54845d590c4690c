#!/usr/bin/env bash
# The project's test command: installs what a fresh machine lacks, then checks formatting and
# lints, runs every test, and builds the runtime for the microcontroller targets.
set -euo pipefail
cd "$(dirname "$0")/.."

# The last line says what passed, failed and was skipped, also when a step fails (the EXIT
# trap): the steps, and the tests `cargo test` ran (summed from its `test result:` lines).
results=$(mktemp)
steps_passed=0 steps_failed=0 steps_skipped=0 current="" current_skipped=0
finish_step() {
  [[ -n $current ]] || return 0
  if ((current_skipped)); then steps_skipped=$((steps_skipped + 1)); else steps_passed=$((steps_passed + 1)); fi
  current=""
}
step() {
  finish_step
  current="$*" current_skipped=0
  printf '\n== %s\n' "$*"
}
skipped() {
  echo "SKIPPED: $*"
  current_skipped=1
}
summary() {
  local status=$?
  if ((status != 0)) && [[ -n $current ]]; then
    steps_failed=$((steps_failed + 1))
    current=""
  fi
  finish_step
  local tests
  tests=$(awk '/^test result:/ { p += $4; f += $6; i += $8 }
               END { printf "%d passed, %d failed, %d ignored", p, f, i }' "$results")
  rm -f "$results"
  printf '\n== summary\nsteps: %d passed, %d failed, %d skipped; tests: %s\n' \
    "$steps_passed" "$steps_failed" "$steps_skipped" "$tests"
  exit "$status"
}
trap summary EXIT

step "toolchain components and targets"
rustup component add rustfmt clippy >/dev/null 2>&1 || true
rustup target add thumbv7em-none-eabihf thumbv6m-none-eabi wasm32-unknown-unknown

step "reference programs (Radiance's ies2rad, oconv and rtrace from the pyradiance wheel, for the photometry and Radiance tests)"
python3 -m pip install --quiet --disable-pip-version-check --root-user-action=ignore pyradiance ||
    skipped "pyradiance unavailable; the comparisons with Radiance will skip"

step "a browser for the page's test (Debian's chromium and chromium-driver; tests/web.rs drives them)"
if ! command -v chromium >/dev/null || ! command -v chromedriver >/dev/null; then
  as_root() { if [[ $(id -u) -eq 0 ]]; then "$@"; elif command -v sudo >/dev/null; then sudo -n "$@"; else return 1; fi; }
  { as_root apt-get update -qq && as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium chromium-driver; } >/dev/null ||
    echo "SKIPPED: chromium could not be installed; tests/web.rs will skip"
fi

step "a single-node Slurm for the building's test (Debian's slurm-wlm and munge; tests/slurm.rs starts and stops its own daemons)"
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  as_root() { if [[ $(id -u) -eq 0 ]]; then "$@"; elif command -v sudo >/dev/null; then sudo -n "$@"; else return 1; fi; }
  { as_root apt-get update -qq && as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge; } >/dev/null ||
    skipped "slurm-wlm and munge could not be installed; tests/slurm.rs will skip"
fi

step "formatting"
cargo fmt --all -- --check

step "lints (warnings are errors)"
cargo clippy --workspace --all-targets -- -D warnings

step "firmware example: formatting and lints (its own workspace)"
(cd examples/firmware && cargo fmt -- --check &&
    CARGO_TARGET_DIR=../../target/firmware cargo clippy --release -- -D warnings)

step "web example: formatting, lints and unit tests (its own workspace, built for wasm32-unknown-unknown)"
(cd examples/web && cargo fmt -- --check &&
    CARGO_TARGET_DIR=../../target/web cargo clippy --release --target wasm32-unknown-unknown -- -D warnings &&
    CARGO_TARGET_DIR=../../target/web cargo test --release --quiet)

step "documentation (warnings are errors)"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps

step "minimum supported Rust version (rust-version in Cargo.toml)"
msrv=$(sed -n 's/^rust-version = "\(.*\)"/\1/p' Cargo.toml)
rustup toolchain install "$msrv" --profile minimal >/dev/null
CARGO_TARGET_DIR=target/msrv cargo "+$msrv" check --workspace --all-targets

step "runtime for the microcontroller targets"
cargo build -p eigenrad-runtime --release --target thumbv7em-none-eabihf
cargo build -p eigenrad-runtime --release --target thumbv6m-none-eabi

step "firmware template (examples/firmware-template, the runtime README's starting point): formatting, lints, built for thumbv7em-none-eabihf"
(cd examples/firmware-template && cargo fmt -- --check &&
    CARGO_TARGET_DIR=../../target/firmware-template cargo clippy --release -- -D warnings &&
    CARGO_TARGET_DIR=../../target/firmware-template cargo build --release)

step "firmware under QEMU (installs qemu-system-arm when missing; tests/firmware.rs runs it on real bases)"
status=0
scripts/firmware.sh runtime/tests/data/tiny.basis target/firmware/tiny.out >/dev/null || status=$?
if [[ $status -eq 77 ]]; then
  skipped "QEMU is unavailable; the firmware tests in tests/firmware.rs will skip too"
elif [[ $status -ne 0 ]]; then
  exit "$status"
fi

step "tests"
cargo test --workspace 2>&1 | tee -a "$results"

step "fuzz smoke run (runtime decoder and evaluator; scene, OBJ/MTL, photometry, tilt, building manifest, HBJSON, gbXML, weather and controller files)"
if rustup toolchain list | grep -q nightly; then
  command -v cargo-fuzz >/dev/null 2>&1 || cargo install cargo-fuzz --locked
  # Runs a target for `seconds` on inputs up to `max_len` bytes from a copy of its seeds
  # (the fuzzer adds to its corpus); what follows goes to `cargo fuzz run`.
  fuzz() {
    local crate=$1 target=$2 seconds=$3 max_len=$4 seeds=$5 corpus
    shift 5
    corpus=$(mktemp -d)
    cp "$seeds"/* "$corpus"/
    (cd "$crate" && cargo +nightly fuzz run "$@" "$target" "$corpus" -- \
      -max_total_time="$seconds" -max_len="$max_len")
    rm -rf "$corpus"
  }
  fuzz runtime/fuzz decode_eval 30 8192 runtime/fuzz/corpus/decode_eval
  # The host's parsers hold no unsafe code: the targets look for panics, overflows and
  # hangs, which need no sanitizer (and the build is much faster without one). Their seeds
  # are the shipped files themselves.
  seeds=$(mktemp -d)
  mkdir -p "$seeds"/{scene_toml,obj_mtl,photometry,tilt_file,building_manifest,hbjson,gbxml,weather,controller}
  i=0
  for scene in examples/*/scene.toml examples/scaling/*.toml tests/scenes/*.toml; do
    i=$((i + 1)) && cp "$scene" "$seeds/scene_toml/$i.toml"
  done
  for obj in examples/cornell-box/*.obj tests/scenes/*.obj; do
    # The OBJ, a 0xFF byte, then the MTL it names (when it names one that is shipped).
    mtl=$(dirname "$obj")/$(awk '$1 == "mtllib" { print $2; exit }' "$obj")
    { cat "$obj"; printf '\xff'; if [[ -f $mtl ]]; then cat "$mtl"; fi; } >"$seeds/obj_mtl/$(basename "$obj")"
  done
  for ies in examples/*/*.ies precompute/src/scene/photometry/testdata/*.ies; do
    i=$((i + 1)) && { printf '\x00'; cat "$ies"; } >"$seeds/photometry/$i.ies"
  done
  for ldt in examples/*/*.ldt precompute/src/scene/photometry/testdata/*.ldt; do
    i=$((i + 1)) && { printf '\x01'; cat "$ldt"; } >"$seeds/photometry/$i.ldt"
  done
  cp precompute/fuzz/corpus/tilt_file/* "$seeds/tilt_file/"
  cp examples/building/building.toml "$seeds/building_manifest/"
  cp examples/import/*.hbjson examples/import/honeybee/*.hbjson "$seeds/hbjson/"
  cp examples/import/*.xml examples/import/openstudio/*.xml "$seeds/gbxml/"
  # The weather year, and its first two days: whole, it is longer than the inputs fuzzed.
  cp data/weather/*.epw data/weather/*.csv "$seeds/weather/"
  head -n 56 data/weather/greensboro-723170-tmy3.epw >"$seeds/weather/two-days.epw"
  # Controller files: the example's, and one of the tiny test basis the target reads.
  cp examples/office-year/controller.toml precompute/fuzz/corpus/controller/* "$seeds/controller/"
  (cd precompute/fuzz && cargo +nightly fuzz build --sanitizer none)
  for target in scene_toml obj_mtl photometry tilt_file building_manifest hbjson gbxml weather controller; do
    fuzz precompute/fuzz "$target" 15 65536 "$seeds/$target" --sanitizer none
  done
  rm -rf "$seeds"
else
  skipped "no nightly toolchain, cargo-fuzz needs one (the proptest properties still ran)"
fi
