//! A plain reference FFD, written the way the formulas read: local coordinates by the
//! cross-product formulas, then binomial coefficients and `powf` for every control point of
//! every point, with no precomputation. Shared by the integration tests (as an oracle) and the
//! benchmark (as the baseline).

use creature_ffd::glam::Vec3;

/// `C(n, k)` by a running product.
fn binomial(n: usize, k: usize) -> f32 {
    let mut c = 1.0f64;
    for i in 0..k {
        c = c * (n - i) as f64 / (i + 1) as f64;
    }
    c as f32
}

fn bernstein(n: usize, i: usize, x: f32) -> f32 {
    binomial(n, i) * (1.0 - x).powf((n - i) as f32) * x.powf(i as f32)
}

/// Deforms `p` by the trivariate Bernstein sum over `control_points` stored `i` fastest.
pub(crate) fn deform(
    origin: Vec3,
    [s_axis, t_axis, u_axis]: [Vec3; 3],
    [l, m, n]: [usize; 3],
    control_points: &[Vec3],
    p: Vec3,
) -> Vec3 {
    let d = p - origin;
    let tu = t_axis.cross(u_axis);
    let us = u_axis.cross(s_axis);
    let st = s_axis.cross(t_axis);
    let s = tu.dot(d) / tu.dot(s_axis);
    let t = us.dot(d) / us.dot(t_axis);
    let u = st.dot(d) / st.dot(u_axis);
    let mut sum = Vec3::ZERO;
    for k in 0..=n {
        for j in 0..=m {
            for i in 0..=l {
                let w = bernstein(l, i, s) * bernstein(m, j, t) * bernstein(n, k, u);
                sum += control_points[(k * (m + 1) + j) * (l + 1) + i] * w;
            }
        }
    }
    sum
}
