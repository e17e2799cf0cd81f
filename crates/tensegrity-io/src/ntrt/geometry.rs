//! The small vector geometry of placing substructures: rotations about a point, centroids,
//! the normal of an attachment plane and the turn between two directions.

/// `p` rotated by `angle` (radians, right-handed) about `axis` through `centre`.
pub(super) fn rotate(p: [f64; 3], centre: [f64; 3], axis: [f64; 3], angle: f64) -> [f64; 3] {
    let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    let k = axis.map(|x| x / n);
    let v: [f64; 3] = std::array::from_fn(|d| p[d] - centre[d]);
    let kxv = [
        k[1] * v[2] - k[2] * v[1],
        k[2] * v[0] - k[0] * v[2],
        k[0] * v[1] - k[1] * v[0],
    ];
    let kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    let (s, c) = angle.sin_cos();
    std::array::from_fn(|d| centre[d] + v[d] * c + kxv[d] * s + k[d] * kv * (1.0 - c))
}

pub(super) fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|d| a[d] + b[d])
}

pub(super) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|d| a[d] - b[d])
}

pub(super) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `v` over its length (none for a zero or non-finite vector).
pub(super) fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (n > 0.0 && n.is_finite()).then(|| v.map(|x| x / n))
}

pub(super) fn centroid(points: &[[f64; 3]]) -> [f64; 3] {
    let n = points.len().max(1) as f64;
    let sum = points.iter().fold([0.0; 3], |s, p| add(s, *p));
    sum.map(|x| x / n)
}

/// The unit normal (p₁ − p₀) × (p₂ − p₀) of the first three points.
pub(super) fn plane_normal(p: &[[f64; 3]]) -> Result<[f64; 3], String> {
    unit(cross(sub(p[1], p[0]), sub(p[2], p[0])))
        .ok_or_else(|| "its first three attachment points are on a line".to_string())
}

/// The rotation (axis, angle) that turns the direction of `a` onto that of `b` (NTRT's:
/// none when they agree to 10⁻⁵, a half turn about `fallback` when opposite).
pub(super) fn between(
    a: [f64; 3],
    b: [f64; 3],
    fallback: [f64; 3],
) -> Result<([f64; 3], f64), String> {
    let why = || "an attachment point is at the centre of the attachments".to_string();
    let (a, b) = (unit(a).ok_or_else(why)?, unit(b).ok_or_else(why)?);
    let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if norm(sub(a, b)) < 1e-5 {
        return Ok(([0.0, 0.0, 1.0], 0.0));
    }
    if norm(add(a, b)) < 1e-5 {
        return Ok((fallback, std::f64::consts::PI));
    }
    let dot = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]).clamp(-1.0, 1.0);
    Ok((unit(cross(a, b)).ok_or_else(why)?, dot.acos()))
}

pub(super) fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}
