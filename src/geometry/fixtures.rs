//! Grounds the geometry's tests share.

use super::Ground;

/// Four triangles over the 4 m square about the origin, rising to a peak `height` (m) high at
/// its centre.
pub(crate) fn pyramid(height: f64) -> Ground {
    pyramid_over(2.0, height)
}

/// Four triangles over the square of half-side `half` (m) about the origin, rising to a peak
/// `height` (m) high at its centre.
pub(crate) fn pyramid_over(half: f64, height: f64) -> Ground {
    let peak = [0.0, height, 0.0];
    let c = [
        [-half, 0.0, -half],
        [half, 0.0, -half],
        [half, 0.0, half],
        [-half, 0.0, half],
    ];
    let tris: Vec<[[f64; 3]; 3]> = (0..4).map(|k| [c[k], c[(k + 1) % 4], peak]).collect();
    Ground::surface(&tris).unwrap()
}
