#!/usr/bin/env bash
# The project's test command: installs what a fresh machine lacks, then checks formatting and
# lints, runs every test, and builds the runtime for the microcontroller targets.
set -euo pipefail
cd "$(dirname "$0")/.."

step() { printf '\n== %s\n' "$*"; }

step "toolchain components and targets"
rustup component add rustfmt clippy >/dev/null 2>&1 || true
rustup target add thumbv7em-none-eabihf thumbv6m-none-eabi

step "formatting"
cargo fmt --all -- --check

step "lints (warnings are errors)"
cargo clippy --workspace --all-targets -- -D warnings

step "firmware example: formatting and lints (its own workspace)"
(cd examples/firmware && cargo fmt -- --check &&
    CARGO_TARGET_DIR=../../target/firmware cargo clippy --release -- -D warnings)

step "runtime for the microcontroller targets"
cargo build -p eigenrad-runtime --release --target thumbv7em-none-eabihf
cargo build -p eigenrad-runtime --release --target thumbv6m-none-eabi

step "tests"
cargo test --workspace
