//! Fuzz target `generate_2d`: see `creature_fuzz::generate_2d` for what it checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|input: creature_fuzz::generate_2d::Input| {
    creature_fuzz::generate_2d::run(&input)
});
