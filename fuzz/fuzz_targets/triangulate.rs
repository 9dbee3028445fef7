//! Fuzz target `triangulate`: see `creature_fuzz::triangulate` for what it checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|input: creature_fuzz::triangulate::Input| {
    creature_fuzz::triangulate::run(&input)
});
