//! A fixed workload for profiling the texture pass: the 256² albedo and normal map of the 16
//! creatures of the `texture_256_only` bench (seeds 0–15), rendered `ROUNDS` times (first
//! argument, default 1), with a cheap checksum of the images (their byte sums) so nothing is
//! optimised away and the run's time is the renders'.
//!
//! ```sh
//! cargo build --release -p creature --example texture_profile
//! valgrind --tool=callgrind --toggle-collect='creature::d2::texture::render_texture*' \
//!     target/release/examples/texture_profile
//! ```

#![allow(clippy::expect_used)]

use creature::{d2, generate_2d};

fn main() {
    let rounds: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(1);
    let plain = d2::Params::DEFAULT.with_texture(false);
    let creatures: Vec<_> = (0..16u64)
        .map(|seed| {
            let c = generate_2d(seed, &plain).expect("valid");
            let options = d2::TextureOptions::DEFAULT.with_noise_seed((seed ^ (seed >> 32)) as u32);
            (c.balls, c.bounds, options)
        })
        .collect();
    let mut checksum = 0u64;
    for _ in 0..rounds {
        for (balls, bounds, options) in &creatures {
            let (albedo, normals) = d2::render_texture(balls, *bounds, options).expect("valid");
            for image in [&albedo.rgba, &normals.rgba] {
                let sum: u64 = image.iter().map(|&b| u64::from(b)).sum();
                checksum = checksum.wrapping_mul(31).wrapping_add(sum);
            }
        }
    }
    println!("{checksum:016x}");
}
