//! The `eigenrad` command line.
fn main() {}
