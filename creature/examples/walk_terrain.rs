//! A walker crossing procedural hills, slopes and steps to a point 10 body lengths away, driven
//! live by `d3::Animator` at 60 updates a second: prints where it is each second and, at the
//! end, how far its planted feet ever were from the ground's surface.
//!
//! `cargo run --release --example walk_terrain -- [SEED]`

#![allow(clippy::std_instead_of_core, clippy::std_instead_of_alloc)]

use creature::d3::{Animator, Intent, Kind, Params, generate};
use creature::gait::Ground;
use creature::glam::Vec3;
use creature::terrain::{TerrainParams, terrain};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let seed: u64 = std::env::args()
        .nth(1)
        .map(|s| s.parse())
        .transpose()?
        .unwrap_or(7);
    let walker = generate(
        seed,
        &Params::DEFAULT.with_kind(Kind::Walker).with_clips(false),
    )?;
    let length = walker.length;
    // Hills as high as the walker is long, a 15° slope, steps a tenth of its length.
    let params = TerrainParams::DEFAULT
        .with_extent(30.0 * length, 241)
        .with_hills(length, 6.0 * length)
        .with_slope(15.0)
        .with_steps(0.1 * length, 3.0 * length);
    let ground = terrain(seed, &params)?;
    let target = Vec3::new(6.0, 0.0, 8.0) * length;
    let mut animator = Animator::new(&walker)?;
    let setup = walker.gait.as_ref().ok_or("a walker has a gait")?;
    let mut worst = 0.0f32;
    for frame in 0..60 * 120 {
        animator.update(1.0 / 60.0, Intent::GoTo(target), &ground)?;
        // The planted feet's joints, as posed, against the ground under them.
        let world = animator.world_transforms();
        for (&hip, state) in setup
            .hip_joints
            .iter()
            .zip(animator.controller().leg_states())
        {
            let foot = Vec3::from(world[hip + 2].translation);
            let under = ground.cast_down_point(foot + Vec3::Y * length, 4.0 * length);
            if let (true, Some(under)) = (state.planted, under) {
                worst = worst.max((foot.y - under.y).abs() / length);
            }
        }
        let at = animator.position();
        let left = Vec3::new(target.x - at.x, 0.0, target.z - at.z).length() / length;
        if frame % 60 == 0 {
            println!(
                "{:>3} s: at ({:6.2}, {:6.2}, {:6.2}) m, heading {:5.2} rad, {left:5.2} body lengths to go",
                frame / 60,
                at.x,
                at.y,
                at.z,
                animator.heading()
            );
        }
        if left < 0.3 {
            println!("arrived after {:.1} s", frame as f32 / 60.0);
            break;
        }
    }
    println!("planted feet within {worst:.4} body lengths of the ground");
    Ok(())
}
