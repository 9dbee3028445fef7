//! Fuzz target `image_png`: see `creature_fuzz::export` for what it checks.
#![no_main]

libfuzzer_sys::fuzz_target!(
    |input: creature_fuzz::export::Input| creature_fuzz::export::run(&input)
);
