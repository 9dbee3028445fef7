//! Fuzz target `metaball_3d`: see `creature_fuzz::metaball_3d` for what it checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|input: creature_fuzz::metaball_3d::Input| {
    creature_fuzz::metaball_3d::run(&input)
});
