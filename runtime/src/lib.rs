#![no_std]
//! eigenrad runtime.
