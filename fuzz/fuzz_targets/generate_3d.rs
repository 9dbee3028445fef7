//! Fuzz target `generate_3d`: see `creature_fuzz::generate_3d` for what it checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|input: creature_fuzz::generate_3d::Input| {
    creature_fuzz::generate_3d::run(&input)
});
