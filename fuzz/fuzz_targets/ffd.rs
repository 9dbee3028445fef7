//! Fuzz target `ffd`: see `creature_fuzz::ffd` for what it checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|input: creature_fuzz::ffd::Input| creature_fuzz::ffd::run(&input));
