//! Tests of the photometric readers.
