//! Domains: what Delaunay refinement knows of the geometry, asked as an oracle (DESIGN.md
//! layer 3; Rineau's thesis §3.1–3.2: the domain is known only through "which subdomain
//! contains this point" and "where does this segment cross the surface").
//!
//! A domain answers:
//! - [`Domain::classify`]: the label of a point (0 outside, > 0 a subdomain);
//! - [`Domain::bbox`]: a box that strictly contains every subdomain;
//! - [`Domain::error_bound`]: how close to the surface a surface point must be;
//! - [`Domain::seeds`]: surface points given by the user.
//!
//! On top of these, [`crossing`] finds where a segment crosses the surface (bisection on the
//! label), and [`initial_points`] finds points on every connected component of the surface.
//!
//! Invariants: `bbox` is non-degenerate and finite; the error bound is positive; a
//! classification never returns a negative label (a callback that does is an error).

mod functions;
mod initial;

pub use functions::{FunctionDomain, Oracle};
pub use initial::initial_points;

use crate::error::Result;
use crate::geometry::{dist, dist2, midpoint};
use crate::predicates::Point;

/// An axis-aligned box `lo..=hi`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BBox {
    pub lo: Point,
    pub hi: Point,
}

impl BBox {
    /// The box `[xmin ymin zmin xmax ymax zmax]`, checked: finite, `min < max` on every axis.
    pub fn from_array(b: &[f64; 6]) -> std::result::Result<BBox, String> {
        let (lo, hi) = ([b[0], b[1], b[2]], [b[3], b[4], b[5]]);
        if let Some(v) = b.iter().find(|v| !v.is_finite()) {
            return Err(format!("bbox has a non-finite value {v}"));
        }
        if let Some(k) = (0..3).find(|&k| lo[k] >= hi[k]) {
            let axis = ["x", "y", "z"][k];
            return Err(format!(
                "bbox is empty along {axis}: min {} is not below max {}",
                lo[k], hi[k]
            ));
        }
        let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if scale > 1e30 {
            return Err(format!(
                "bbox coordinate {scale:e} is beyond 1e30, where refinement constructions overflow"
            ));
        }
        Ok(BBox { lo, hi })
    }

    pub fn diagonal(&self) -> f64 {
        dist(&self.lo, &self.hi)
    }

    pub fn contains(&self, p: &Point) -> bool {
        (0..3).all(|k| self.lo[k] <= p[k] && p[k] <= self.hi[k])
    }

    /// The part of `a + s (b - a)`, `s` in `[0, end]` (`end` may be infinite: a ray), inside
    /// the box, as its two end points and whether each is an end of the original segment
    /// (`false`: a point where the segment crosses the box boundary). `None` if it misses.
    pub fn clip(&self, a: &Point, b: &Point, end: f64) -> Option<Clipped> {
        let d: Point = std::array::from_fn(|k| b[k] - a[k]);
        let (mut s0, mut s1) = (0.0f64, end);
        for k in 0..3 {
            if d[k] == 0.0 {
                if a[k] < self.lo[k] || a[k] > self.hi[k] {
                    return None;
                }
                continue;
            }
            let (u, v) = ((self.lo[k] - a[k]) / d[k], (self.hi[k] - a[k]) / d[k]);
            s0 = s0.max(u.min(v));
            s1 = s1.min(u.max(v));
        }
        if s0 >= s1 || s0.is_nan() || !s1.is_finite() {
            return None;
        }
        let at = |s: f64| self.clamp(&std::array::from_fn(|k| a[k] + s * d[k]));
        Some(Clipped {
            start: if s0 > 0.0 { at(s0) } else { *a },
            end: if s1 < end { at(s1) } else { *b },
            start_is_a: s0 <= 0.0,
            end_is_b: s1 >= end,
        })
    }

    /// The nearest point of the box.
    pub fn clamp(&self, p: &Point) -> Point {
        std::array::from_fn(|k| p[k].clamp(self.lo[k], self.hi[k]))
    }
}

/// A segment clipped to a box (see [`BBox::clip`]).
#[derive(Clone, Copy, Debug)]
pub struct Clipped {
    pub start: Point,
    pub end: Point,
    pub start_is_a: bool,
    pub end_is_b: bool,
}

/// The geometry as an oracle (see the module documentation).
pub trait Domain {
    /// The subdomain containing `p` inside the box: 0 outside, > 0 a subdomain. Errors: the
    /// user's function failed (NaN, negative label).
    fn classify(&self, p: &Point) -> Result<i32>;

    fn bbox(&self) -> &BBox;

    /// Largest distance from a computed surface point to the surface, along the segment that
    /// found it.
    fn error_bound(&self) -> f64;

    /// Points the user gave on the surface, to reach components the search may miss.
    fn seeds(&self) -> &[Point];

    /// [`Domain::classify`], with 0 outside the box.
    fn label(&self, p: &Point) -> Result<i32> {
        if self.bbox().contains(p) {
            self.classify(p)
        } else {
            Ok(0)
        }
    }
}

/// Where a segment crosses the surface between two subdomains.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    pub point: Point,
    /// The label before the crossing (from the segment's start) and after it.
    pub labels: (i32, i32),
}

/// Bisection on `a..b`, where `a` has label `la` and `b` a different label `lb`, down to the
/// domain's error bound. The crossing point lies within that bound of a point where the
/// label changes; its labels are those of the last bracket.
pub fn crossing(domain: &dyn Domain, a: &Point, la: i32, b: &Point, lb: i32) -> Result<Crossing> {
    let (mut a, mut b, mut lb) = (*a, *b, lb);
    let bound2 = domain.error_bound() * domain.error_bound();
    // Each halving shrinks the bracket; 200 halvings reach any bound above 2^-200 * length,
    // and a bracket of two adjacent doubles stops earlier.
    for _ in 0..200 {
        if dist2(&a, &b) <= bound2 {
            break;
        }
        let m = midpoint(&a, &b);
        if m == a || m == b {
            break;
        }
        let lm = domain.label(&m)?;
        if lm == la {
            a = m;
        } else {
            b = m;
            lb = lm;
        }
    }
    Ok(Crossing {
        point: midpoint(&a, &b),
        labels: (la, lb),
    })
}

/// The first crossing along `a..b` (labels `la`, `lb` at the ends) found by testing the
/// segment at points at most `step` apart (`step` infinite: the ends only), at most
/// `max_samples` of them.
pub fn first_crossing(
    domain: &dyn Domain,
    a: &Point,
    la: i32,
    b: &Point,
    lb: i32,
    step: f64,
    max_samples: usize,
) -> Result<Option<Crossing>> {
    let length = dist(a, b);
    let pieces = if step.is_finite() && step > 0.0 {
        ((length / step).ceil() as usize).clamp(1, max_samples + 1)
    } else {
        1
    };
    let mut prev = *a;
    for k in 1..pieces {
        let s = k as f64 / pieces as f64;
        let p: Point = std::array::from_fn(|i| a[i] + s * (b[i] - a[i]));
        let lp = domain.label(&p)?;
        if lp != la {
            return crossing(domain, &prev, la, &p, lp).map(Some);
        }
        prev = p;
    }
    if lb != la {
        return crossing(domain, &prev, la, b, lb).map(Some);
    }
    Ok(None)
}
