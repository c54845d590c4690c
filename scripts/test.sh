#!/usr/bin/env bash
# The project's test command: installs what a fresh machine lacks, then checks formatting and
# lints, runs every test, and builds the runtime for the microcontroller targets.
set -euo pipefail
cd "$(dirname "$0")/.."

step() { printf '\n== %s\n' "$*"; }

step "toolchain components and targets"
rustup component add rustfmt clippy >/dev/null 2>&1 || true
rustup target add thumbv7em-none-eabihf thumbv6m-none-eabi wasm32-unknown-unknown

step "reference programs (Radiance's ies2rad, oconv and rtrace from the pyradiance wheel, for the photometry and Radiance tests)"
python3 -m pip install --quiet --disable-pip-version-check --root-user-action=ignore pyradiance ||
    echo "SKIPPED: pyradiance unavailable; the comparisons with Radiance will skip"

step "a browser for the page's test (Debian's chromium and chromium-driver; tests/web.rs drives them)"
if ! command -v chromium >/dev/null || ! command -v chromedriver >/dev/null; then
  as_root() { if [[ $(id -u) -eq 0 ]]; then "$@"; elif command -v sudo >/dev/null; then sudo -n "$@"; else return 1; fi; }
  { as_root apt-get update -qq && as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium chromium-driver; } >/dev/null ||
    echo "SKIPPED: chromium could not be installed; tests/web.rs will skip"
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

step "firmware under QEMU (installs qemu-system-arm when missing; tests/firmware.rs runs it on real bases)"
status=0
scripts/firmware.sh runtime/tests/data/tiny.basis target/firmware/tiny.out >/dev/null || status=$?
if [[ $status -eq 77 ]]; then
  echo "SKIPPED: QEMU is unavailable; the firmware tests in tests/firmware.rs will skip too"
elif [[ $status -ne 0 ]]; then
  exit "$status"
fi

step "tests"
cargo test --workspace

step "fuzz smoke run (runtime decoder and evaluator)"
if rustup toolchain list | grep -q nightly; then
  command -v cargo-fuzz >/dev/null 2>&1 || cargo install cargo-fuzz --locked
  corpus=$(mktemp -d)
  cp runtime/fuzz/corpus/decode_eval/* "$corpus"/
  (cd runtime/fuzz && cargo +nightly fuzz run decode_eval "$corpus" -- -max_total_time=30 -max_len=8192)
  rm -rf "$corpus"
else
  echo "SKIPPED: no nightly toolchain, cargo-fuzz needs one (the proptest properties still ran)"
fi
