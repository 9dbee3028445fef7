//! Fuzz target `skin`: see `creature_fuzz::skin` for what it checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|input: creature_fuzz::skin::Input| creature_fuzz::skin::run(&input));
