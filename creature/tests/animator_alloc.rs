//! `Animator::update` allocates nothing once the animator is built: a counting global
//! allocator (this test binary's only one) watches walkers, fliers, swimmers and slitherers standing,
//! moving, turning and going to targets over a plane and over procedural terrain, with variable time steps.

// The allocator below needs `unsafe impl GlobalAlloc`; it only forwards to the system's.
#![allow(unsafe_code)]
// Helpers outside `#[test]` functions unwrap too: a failure there is a test failure.
#![allow(clippy::unwrap_used)]

use core::alloc::{GlobalAlloc, Layout};
use core::cell::Cell;
use core::sync::atomic::{AtomicUsize, Ordering};
use std::alloc::System;

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

use creature::d3::{self, Animator, Intent, Kind};
use creature::gait::{Ground, Plane};
use creature::glam::Vec3;
use creature::terrain::{TerrainParams, terrain};

/// `frames` updates of `animator` on `ground`: standing, walking and turning both ways, going
/// to a target, with variable `dt` (0 and a hitch included).
fn drive(animator: &mut Animator, ground: &dyn Ground, length: f32, frames: u32) {
    for f in 0..frames {
        let intent = match (f / 60) % 4 {
            0 => Intent::Stand,
            1 => Intent::Move {
                velocity: Vec3::new(0.3, 0.0, 1.0) * length,
                turn_rate: 0.6,
            },
            2 => Intent::Move {
                velocity: Vec3::Z * length,
                turn_rate: -1.0,
            },
            _ => Intent::GoTo(Vec3::new(5.0, 0.0, -5.0) * length),
        };
        let dt = match f % 13 {
            3 => 0.0,
            7 => 0.5,
            _ => 1.0 / (50.0 + (f % 3) as f32 * 10.0),
        };
        animator.update(dt, intent, ground).unwrap();
    }
}

#[test]
fn an_update_allocates_nothing() {
    let hills = terrain(3, &TerrainParams::DEFAULT).unwrap();
    let kinds = [Kind::Walker, Kind::Flier, Kind::Swimmer, Kind::Slitherer];
    for (seed, kind) in [1, 2, 3].into_iter().flat_map(|s| kinds.map(|k| (s, k))) {
        let c = d3::generate(seed, &d3::Params::DEFAULT.with_kind(kind).with_clips(false)).unwrap();
        for ground in [&Plane::GROUND as &dyn Ground, &hills] {
            let mut animator = Animator::new(&c).unwrap();
            // The first update starts afresh; then none allocates.
            animator.update(0.0, Intent::Stand, ground).unwrap();
            let n = allocations_in(|| drive(&mut animator, ground, c.length, 600));
            assert_eq!(n, 0, "{kind:?} {seed}: {n} allocations in 600 updates");
        }
    }
}

#[test]
fn a_hoppers_update_allocates_nothing() {
    let hills = terrain(3, &TerrainParams::DEFAULT).unwrap();
    let params = d3::Params::DEFAULT
        .with_kind(Kind::Walker)
        .with_clips(false)
        .with_hop_chance(1.0);
    for seed in [7, 11] {
        let c = d3::generate(seed, &params).unwrap();
        let hop = c.gait.as_ref().unwrap().hop_speed().unwrap();
        for ground in [&Plane::GROUND as &dyn Ground, &hills] {
            let mut animator = Animator::new(&c).unwrap();
            animator.update(0.0, Intent::Stand, ground).unwrap();
            let mut hopped = false;
            let n = allocations_in(|| {
                for f in 0..300 {
                    let turn_rate = if f < 150 { 0.3 } else { -0.3 };
                    let intent = Intent::Move {
                        velocity: Vec3::Z * hop,
                        turn_rate,
                    };
                    animator.update(1.0 / 60.0, intent, ground).unwrap();
                    hopped |= animator.controller().gait() == creature::gait::Gait::Hop;
                }
            });
            assert_eq!(n, 0, "hopper {seed}: {n} allocations in 300 updates");
            assert!(hopped, "hopper {seed} never hopped");
        }
    }
}
