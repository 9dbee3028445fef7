//! A plain marching squares, as one would first write it: a segment list per cell, joined
//! into polylines through a `BTreeMap` keyed by quantised endpoints, saddles always split. Used
//! by the outline bench as the baseline.

#![allow(unreachable_pub)]

use alloc::collections::BTreeMap;

use creature_march::glam::Vec2;

/// Closed polylines of `values >= iso` (outside the grid is outside), in sample coordinates.
pub fn contours(values: &[f32], width: usize, height: usize, iso: f32) -> Vec<Vec<Vec2>> {
    let at = |x: i64, y: i64| -> f32 {
        if x < 0 || y < 0 || x >= width as i64 || y >= height as i64 {
            f32::NEG_INFINITY
        } else {
            values[y as usize * width + x as usize]
        }
    };
    let cross = |a: (i64, i64), b: (i64, i64)| -> Vec2 {
        let (va, vb) = (at(a.0, a.1), at(b.0, b.1));
        let pa = Vec2::new(a.0 as f32, a.1 as f32);
        let pb = Vec2::new(b.0 as f32, b.1 as f32);
        if !va.is_finite() {
            return pb;
        }
        if !vb.is_finite() {
            return pa;
        }
        pa + (pb - pa) * ((iso - va) / (vb - va))
    };
    let mut segments: Vec<(Vec2, Vec2)> = Vec::new();
    for y in -1..height as i64 {
        for x in -1..width as i64 {
            let c = [(x, y), (x + 1, y), (x + 1, y + 1), (x, y + 1)];
            let inside: Vec<bool> = c.iter().map(|&(i, j)| at(i, j) >= iso).collect();
            let mut starts = Vec::new();
            let mut ends = Vec::new();
            for k in 0..4 {
                let (a, b) = (inside[k], inside[(k + 1) % 4]);
                if a && !b {
                    starts.push(k);
                }
                if !a && b {
                    ends.push(k);
                }
            }
            // Saddles split (the reference does not decide); others have one pair.
            for (s, e) in starts.iter().zip(ends.iter().rev()) {
                let p = cross(c[*s], c[(*s + 1) % 4]);
                let q = cross(c[(*e + 1) % 4], c[*e]);
                segments.push((p, q));
            }
        }
    }
    let key = |p: Vec2| ((p.x * 4096.0).round() as i64, (p.y * 4096.0).round() as i64);
    let mut by_start: BTreeMap<(i64, i64), usize> = BTreeMap::new();
    for (i, s) in segments.iter().enumerate() {
        by_start.insert(key(s.0), i);
    }
    let mut used = vec![false; segments.len()];
    let mut rings = Vec::new();
    for i in 0..segments.len() {
        if used[i] {
            continue;
        }
        let mut ring = Vec::new();
        let mut j = i;
        while !used[j] {
            used[j] = true;
            ring.push(segments[j].0);
            match by_start.get(&key(segments[j].1)) {
                Some(&n) => j = n,
                None => break,
            }
        }
        rings.push(ring);
    }
    rings
}
