//! Fuzz target `march_grid`: see `creature_fuzz::march_grid` for what it checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|input: creature_fuzz::march_grid::Input| {
    creature_fuzz::march_grid::run(&input)
});
