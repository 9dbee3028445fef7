//! Fuzz target `gait`: see `creature_fuzz::gait` for what it checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|input: creature_fuzz::gait::Input| creature_fuzz::gait::run(&input));
