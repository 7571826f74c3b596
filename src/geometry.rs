//! Floating-point vector arithmetic for constructions and measurements (circumcenters,
//! normals, angles, distances). Never used to decide topology: decisions go through
//! [`crate::predicates`].

use crate::predicates::Point;

#[inline]
pub fn sub(a: &Point, b: &Point) -> Point {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline]
pub fn cross(u: &Point, v: &Point) -> Point {
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

#[inline]
pub fn dot(u: &Point, v: &Point) -> f64 {
    u[0] * v[0] + u[1] * v[1] + u[2] * v[2]
}

#[inline]
pub fn norm(u: &Point) -> f64 {
    dot(u, u).sqrt()
}

#[inline]
pub fn dist2(a: &Point, b: &Point) -> f64 {
    let d = sub(a, b);
    dot(&d, &d)
}
