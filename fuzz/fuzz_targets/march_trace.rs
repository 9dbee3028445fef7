//! Fuzz target `march_trace`: see `creature_fuzz::march_trace` for what it checks.
#![no_main]

libfuzzer_sys::fuzz_target!(|input: creature_fuzz::march_trace::Input| {
    creature_fuzz::march_trace::run(&input)
});
