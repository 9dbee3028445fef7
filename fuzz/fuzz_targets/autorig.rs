//! Fuzz target `autorig`: see `creature_fuzz::autorig` for what it checks.
#![no_main]

libfuzzer_sys::fuzz_target!(
    |input: creature_fuzz::autorig::Input| creature_fuzz::autorig::run(&input)
);
