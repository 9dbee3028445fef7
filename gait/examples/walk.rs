//! A quadruped walking, turning and stopping on a height field, printing its feet every half
//! second. Run: `cargo run -p creature-gait --example walk`

use creature_gait::glam::{Quat, Vec2, Vec3};
use creature_gait::{Chain, Controller, GaitError, GaitOptions, HeightField, Leg, Pose};

fn main() -> Result<(), GaitError> {
    let ground = HeightField::from_fn(Vec2::splat(-30.0), 0.5, 121, 121, |x, z| {
        0.25 * (x * 0.4).sin() * (z * 0.3).cos()
    })?;
    let mut legs = Vec::new();
    for z in [0.45, -0.45] {
        for side in [1.0, -1.0] {
            legs.push(Leg::new(
                Vec3::new(0.25 * side, 0.0, z),
                Vec3::new(0.35 * side, -0.8, z),
                0.5,
                0.5,
            ));
        }
    }
    let mut creature = Controller::new(&legs, &GaitOptions::DEFAULT)?;
    let tail = creature.add_chain(Chain::new(Vec3::new(0.0, 0.0, -0.6), Vec3::NEG_Z, 6, 0.15))?;
    creature.set_head(Vec3::new(0.0, 0.1, 0.7))?;

    let dt = 1.0 / 60.0;
    let (mut position, mut yaw) = (Vec3::ZERO, 0.0f32);
    for frame in 0..600 {
        let t = frame as f32 * dt;
        // Walk, turn left while walking, then stop.
        let (speed, turn) = match t {
            t if t < 4.0 => (1.2, 0.0),
            t if t < 7.0 => (0.8, 0.6),
            _ => (0.0, 0.0),
        };
        let rotation = Quat::from_rotation_y(yaw);
        let velocity = rotation * Vec3::new(0.0, 0.0, speed);
        position += velocity * dt;
        yaw += turn * dt;
        let y = ground.height(position.x, position.z).unwrap_or(0.0) + 0.8;
        let pose = Pose::new(Vec3::new(position.x, y, position.z), rotation);
        creature.update(dt, pose, velocity, Vec3::Y * turn, &ground)?;
        if frame % 30 == 0 {
            let feet: Vec<String> = creature
                .leg_states()
                .iter()
                .map(|leg| {
                    let mark = if leg.planted { "down" } else { "up  " };
                    format!(
                        "{mark} ({:5.2}, {:5.2}, {:5.2})",
                        leg.foot.x, leg.foot.y, leg.foot.z
                    )
                })
                .collect();
            let m = creature.metrics();
            println!(
                "t = {t:4.1} s  {}  bob {:+.3} m  head yaw {:+.2}  tail tip {:.2}  margin {:?}",
                feet.join("  "),
                creature.body().bob,
                creature.look().yaw,
                creature.chain(tail)?[6],
                m.stability_margin.map(|v| (v * 100.0).round() / 100.0),
            );
        }
    }
    Ok(())
}
