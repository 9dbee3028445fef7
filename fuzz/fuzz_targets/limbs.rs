//! Fuzz target `limbs`: see `creature_fuzz::limbs` for what it checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|input: creature_fuzz::limbs::Input| creature_fuzz::limbs::run(&input));
