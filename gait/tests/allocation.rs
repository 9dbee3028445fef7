//! `Controller::update` allocates nothing once the controller is built: a counting global
//! allocator (this test binary's only one) watches a walk with turns, stops, arms, chains, a
//! look target and blend ramps over a height field and over a plane.

// The allocator below needs `unsafe impl GlobalAlloc`; it only forwards to the system's.
#![allow(unsafe_code)]
// Helpers outside `#[test]` functions unwrap too: a failure there is a test failure.
#![allow(clippy::unwrap_used)]

mod support;

use core::alloc::{GlobalAlloc, Layout};
use core::cell::Cell;
use core::sync::atomic::{AtomicUsize, Ordering};
use std::alloc::System;

use creature_gait::glam::{Quat, Vec3};
use creature_gait::{
    Chain, Controller, Gait, GaitOptions, GaitSpeeds, Ground, Leg, LimbKind, Plane, Pose,
};
use support::{creature_legs, random_terrain};

/// Counts the allocations (and reallocations) made by threads that switched counting on.
struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

std::thread_local! {
    static COUNTING: Cell<bool> = const { Cell::new(false) };
}

fn note() {
    if COUNTING.try_with(Cell::get).unwrap_or(false) {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
    }
}

// SAFETY: every call is forwarded unchanged to the system allocator.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note();
        // SAFETY: the caller's contract is passed on unchanged.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note();
        // SAFETY: as above.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note();
        // SAFETY: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by this thread while `f` runs.
fn allocations_in(f: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    COUNTING.with(|c| c.set(true));
    f();
    COUNTING.with(|c| c.set(false));
    ALLOCATIONS.load(Ordering::Relaxed) - before
}

/// `frames` updates: speeds from standing to running, turns both ways and in place, variable
/// `dt` (0 included), the body following the ground's height.
fn walk(c: &mut Controller, ground: &dyn Ground, height: impl Fn(f32, f32) -> f32, frames: u32) {
    let mut position = Vec3::ZERO;
    let mut yaw = 0.0f32;
    for f in 0..frames {
        let phase = (f / 120) % 5;
        let speed = [0.0, 0.4, 1.5, 4.0, 0.0][phase as usize];
        let turn = [0.0, 0.6, -1.2, 0.3, 2.5][phase as usize];
        let dt = if f % 11 == 3 {
            0.0
        } else {
            1.0 / (50.0 + (f % 3) as f32 * 10.0)
        };
        yaw += turn * dt;
        let velocity = Quat::from_rotation_y(yaw) * Vec3::Z * speed;
        position += velocity * dt;
        position.y = height(position.x, position.z) + 0.8;
        let pose = Pose::new(position, Quat::from_rotation_y(yaw));
        c.update(dt, pose, velocity, Vec3::Y * turn, ground)
            .unwrap();
    }
}

#[test]
fn updates_allocate_nothing_after_the_controller_is_built() {
    let field = random_terrain(5, 0.4);
    let plane = Plane::GROUND;
    let mut legs = creature_legs(3, 1.0);
    legs.push(
        Leg::new(
            Vec3::new(0.3, 0.3, 0.8),
            Vec3::new(0.35, 0.1, 1.0),
            0.3,
            0.3,
        )
        .with_kind(LimbKind::Arm),
    );
    let options = GaitOptions::DEFAULT.with_blend_time(0.2);
    let mut c = Controller::new(&legs, &options).unwrap();
    // Gaits by speed: 1.5 m/s on 1 m legs walks, 4 m/s trots.
    let mut changing = Controller::new(
        &creature_legs(2, 1.0),
        &options.with_gaits(GaitSpeeds::DEFAULT),
    )
    .unwrap();
    // A biped that hops.
    let mut hopper = Controller::new(
        &creature_legs(1, 1.0),
        &options.with_gaits(GaitSpeeds::DEFAULT).with_hop(true),
    )
    .unwrap();
    c.add_chain(Chain::new(Vec3::new(0.0, 0.0, -0.6), Vec3::NEG_Z, 6, 0.15).with_gravity(4.0))
        .unwrap();
    let mut flier = Controller::chains_only(0.5, &options).unwrap();
    flier
        .add_chain(Chain::new(Vec3::ZERO, Vec3::NEG_Y, 3, 0.2).with_gravity(9.81))
        .unwrap();
    let on_field = |x: f32, z: f32| field.height(x, z).unwrap_or(0.0);

    let mut steps = 0;
    let count = allocations_in(|| {
        walk(&mut c, &field, on_field, 600);
        c.set_look_target(Some(Vec3::new(3.0, 1.0, 5.0))).unwrap();
        c.blend_to(0.25).unwrap();
        walk(&mut c, &plane, |_, _| 0.0, 300);
        c.set_look_target(None).unwrap();
        c.blend_to(1.0).unwrap();
        steps = c.leg_states().iter().map(|leg| leg.steps).sum();
        c.reset(Pose::new(Vec3::new(0.0, 0.8, 0.0), Quat::IDENTITY), &field)
            .unwrap();
        walk(&mut c, &field, on_field, 300);
        walk(&mut flier, &plane, |_, _| 2.0, 300);
        walk(&mut changing, &plane, |_, _| 0.0, 480);
        walk(&mut hopper, &plane, |_, _| 0.0, 480);
    });
    assert_eq!(count, 0, "updates allocated {count} times");
    assert!(steps > 50, "{steps} steps");
    assert_ne!(changing.gait(), Gait::Walk, "never changed gait");
    assert_eq!(hopper.gait(), Gait::Hop, "never hopped");
    // The counter works: a controller's construction allocates.
    assert!(allocations_in(|| drop(Controller::new(&legs, &options).unwrap())) > 0);
}
