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

#[inline]
pub fn dist(a: &Point, b: &Point) -> f64 {
    dist2(a, b).sqrt()
}

#[inline]
pub fn add(a: &Point, b: &Point) -> Point {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// The midpoint, computed so that it lies between `a` and `b` coordinate-wise (it stays in any
/// box that holds both).
#[inline]
pub fn midpoint(a: &Point, b: &Point) -> Point {
    std::array::from_fn(|k| 0.5 * a[k] + 0.5 * b[k])
}

/// The signed volume of the tetrahedron `t` (positive when positively oriented).
pub fn tet_volume(t: [&Point; 4]) -> f64 {
    dot(&sub(t[1], t[0]), &cross(&sub(t[2], t[0]), &sub(t[3], t[0]))) / 6.0
}

/// The center of the circle through the triangle's vertices.
pub fn triangle_circumcenter(t: [&Point; 3]) -> Point {
    let (u, v) = (sub(t[1], t[0]), sub(t[2], t[0]));
    let w = cross(&u, &v);
    let (a, b) = (cross(&v, &w), cross(&w, &u));
    let (nu, nv, nw) = (dot(&u, &u), dot(&v, &v), 2.0 * dot(&w, &w));
    std::array::from_fn(|k| t[0][k] + (nu * a[k] + nv * b[k]) / nw)
}

/// The center of the sphere through the tetrahedron's vertices (not finite when they are
/// coplanar in floating point).
pub fn circumcenter(t: [&Point; 4]) -> Point {
    let (u, v, w) = (sub(t[1], t[0]), sub(t[2], t[0]), sub(t[3], t[0]));
    let (nu, nv, nw) = (dot(&u, &u), dot(&v, &v), dot(&w, &w));
    let (vw, wu, uv) = (cross(&v, &w), cross(&w, &u), cross(&u, &v));
    let det2 = 2.0 * dot(&u, &vw);
    std::array::from_fn(|k| t[0][k] + (nu * vw[k] + nv * wu[k] + nw * uv[k]) / det2)
}
