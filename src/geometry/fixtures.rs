//! Grounds the geometry's tests share.

use super::Ground;

/// Four triangles over the 4 m square about the origin, rising to a peak `height` (m) high at
/// its centre.
pub(crate) fn pyramid(height: f64) -> Ground {
    let peak = [0.0, height, 0.0];
    let c = [
        [-2.0, 0.0, -2.0],
        [2.0, 0.0, -2.0],
        [2.0, 0.0, 2.0],
        [-2.0, 0.0, 2.0],
    ];
    let tris: Vec<[[f64; 3]; 3]> = (0..4).map(|k| [c[k], c[(k + 1) % 4], peak]).collect();
    Ground::surface(&tris).unwrap()
}
