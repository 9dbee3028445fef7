//! Fuzz target `metaball_2d`: see `creature_fuzz::metaball_2d` for what it checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|input: creature_fuzz::metaball_2d::Input| {
    creature_fuzz::metaball_2d::run(&input)
});
