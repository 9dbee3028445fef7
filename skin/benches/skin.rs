//! Binding 10,000 vertices to 30 bones with `nearest_k`, and skinning 10,000 vertices with
//! linear blending and dual quaternions, each against a plain reference implementation in the
//! same run.
//!
//! Run: `cargo bench -p creature-skin --bench skin`

// Setup outside the timed code may fail loudly: a broken input is a broken bench.
#![allow(clippy::expect_used)]

use core::hint::black_box;

use creature_skin::glam::{Affine3A, Mat4, Quat, Vec3};
use creature_skin::{Blend, Influences, nearest_k, skin_positions};
use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};

const VERTICES: usize = 10_000;
const BONES: usize = 30;

/// A small deterministic generator (xorshift32), so inputs are the same on every run.
struct Xorshift(u32);

impl Xorshift {
    fn next_f32(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 17;
        self.0 ^= self.0 << 5;
        (self.0 >> 8) as f32 / (1u32 << 24) as f32
    }
}

/// A creature-like body: a 10-bone spine along Z with 10 legs of two bones, and vertices
/// scattered in a shell around the spine.
fn inputs() -> (Vec<Vec3>, Vec<[Vec3; 2]>) {
    let mut rng = Xorshift(0x9e37_79b9);
    let mut bones = Vec::new();
    for i in 0..10 {
        let z = -2.5 + 0.5 * i as f32;
        bones.push([Vec3::Z * z, Vec3::Z * (z + 0.5)]);
    }
    for i in 0..10 {
        let side = if i % 2 == 0 { 1.0 } else { -1.0 };
        let hip = Vec3::new(0.4 * side, 0.0, -2.0 + 0.8 * (i / 2) as f32);
        let knee = hip + Vec3::new(0.5 * side, -0.2, 0.0);
        bones.push([hip, knee]);
        bones.push([knee, knee + Vec3::new(0.0, -0.8, 0.0)]);
    }
    assert_eq!(bones.len(), BONES);
    let vertices = (0..VERTICES)
        .map(|_| {
            let a = rng.next_f32() * core::f32::consts::TAU;
            let r = 0.3 + 0.5 * rng.next_f32();
            Vec3::new(a.cos() * r, a.sin() * r, -2.5 + 5.0 * rng.next_f32())
        })
        .collect();
    (vertices, bones)
}

/// The seed's way, written plainly: distance to every bone with a square root, a full sort,
/// inverse-distance weights, normalised.
fn reference_nearest_k(vertices: &[Vec3], bones: &[[Vec3; 2]]) -> Vec<Influences> {
    vertices
        .iter()
        .map(|&v| {
            let mut d: Vec<(f32, usize)> = bones
                .iter()
                .enumerate()
                .map(|(i, b)| {
                    let axis = b[1] - b[0];
                    let t = ((v - b[0]).dot(axis) / axis.length_squared()).clamp(0.0, 1.0);
                    (v.distance(b[0] + axis * t), i)
                })
                .collect();
            d.sort_by(|a, b| a.0.total_cmp(&b.0));
            let mut inf = Influences::NONE;
            let mut sum = 0.0;
            for (slot, &(dist, i)) in d.iter().take(4).enumerate() {
                inf.joints[slot] = i as u16;
                inf.weights[slot] = 1.0 / (dist * dist).max(1e-12);
                sum += inf.weights[slot];
            }
            for w in &mut inf.weights {
                *w /= sum;
            }
            inf
        })
        .collect()
}

/// Linear blend skinning as one would first write it: blend four `Mat4`s, then transform.
fn reference_lbs(rest: &[Vec3], influences: &[Influences], mats: &[Mat4], out: &mut [Vec3]) {
    for ((p, inf), o) in rest.iter().zip(influences).zip(out.iter_mut()) {
        let mut m = Mat4::ZERO;
        for (j, w) in inf.joints.iter().zip(inf.weights) {
            m += mats[usize::from(*j)] * w;
        }
        *o = m.transform_point3(*p);
    }
}

fn bench(c: &mut Criterion) {
    let (vertices, bones) = inputs();
    let mut group = c.benchmark_group("nearest_k_10k_vertices_30_bones");
    group.throughput(Throughput::Elements(VERTICES as u64));
    group.sample_size(20);
    group.bench_function("creature_skin_nearest_k", |b| {
        b.iter(|| nearest_k(black_box(&vertices), black_box(&bones), 4).expect("valid input"));
    });
    group.bench_function("reference_sort_all", |b| {
        b.iter(|| reference_nearest_k(black_box(&vertices), black_box(&bones)));
    });
    group.finish();

    let influences = nearest_k(&vertices, &bones, 4).expect("valid input");
    let mut rng = Xorshift(0x2545_f491);
    let transforms: Vec<Affine3A> = (0..BONES)
        .map(|_| {
            let q = Quat::from_rotation_y(rng.next_f32() - 0.5)
                * Quat::from_rotation_x(rng.next_f32() - 0.5);
            Affine3A::from_rotation_translation(q, Vec3::new(rng.next_f32(), rng.next_f32(), 0.0))
        })
        .collect();
    let mats: Vec<Mat4> = transforms.iter().map(|&t| Mat4::from(t)).collect();
    let mut group = c.benchmark_group("skin_10k_vertices");
    group.throughput(Throughput::Elements(VERTICES as u64));
    group.sample_size(50);
    for (name, blend) in [
        ("creature_skin_linear", Blend::Linear),
        ("creature_skin_dual_quaternion", Blend::DualQuaternion),
    ] {
        group.bench_function(name, |b| {
            b.iter_batched_ref(
                || vec![Vec3::ZERO; VERTICES],
                |out| {
                    skin_positions(black_box(&vertices), &influences, &transforms, blend, out)
                        .expect("valid input");
                },
                BatchSize::LargeInput,
            );
        });
    }
    group.bench_function("reference_mat4_blend", |b| {
        b.iter_batched_ref(
            || vec![Vec3::ZERO; VERTICES],
            |out| reference_lbs(black_box(&vertices), &influences, &mats, out),
            BatchSize::LargeInput,
        );
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
