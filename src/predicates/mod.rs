//! Exact geometric predicates (DESIGN.md layer 1).
//!
//! Decisions are exact: every function returns the sign of a polynomial in the input
//! coordinates, evaluated exactly. Constructions elsewhere are floating point.
//!
//! Sign conventions (all positive cases are "the expected, non-degenerate" side):
//! - [`orient3d`]`(a,b,c,d)` is the sign of `dot(b-a, cross(c-a, d-a))`: positive when
//!   `(a,b,c,d)` is a positively oriented tetrahedron (the C API's convention). This is the
//!   opposite of Shewchuk's `orient3d`.
//! - [`insphere`]`(a,b,c,d,e)`, for positively oriented `(a,b,c,d)`: positive when `e` lies
//!   strictly inside the circumsphere.
//! - [`power_test`]: the weighted version: positive when the lifted point
//!   `(e, |e|^2 - w_e)` lies strictly below the hyperplane through the lifted `a..d`, i.e.
//!   `e` is in conflict with the tetrahedron in the regular triangulation.
//!
//! The `_sos` variants never return [`Sign::Zero`] for a non-degenerate simplex: exact ties
//! are broken by a symbolic perturbation of the lifted coordinate, `|p|^2 - w_p - eps^(r_p)`
//! ordered by the lexicographic rank `r_p` of the point's coordinates, so the outcome depends
//! on the points only, never on the order in which they are given or inserted.

/// A point of R^3.
pub type Point = [f64; 3];

/// The sign of an exactly evaluated determinant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[repr(i8)]
pub enum Sign {
    Negative = -1,
    Zero = 0,
    Positive = 1,
}

impl Sign {
    /// The sign of a floating-point value known to be exact (or of an exact expansion's top term).
    pub fn of(x: f64) -> Sign {
        if x > 0.0 {
            Sign::Positive
        } else if x < 0.0 {
            Sign::Negative
        } else {
            Sign::Zero
        }
    }

    pub fn negate(self) -> Sign {
        match self {
            Sign::Negative => Sign::Positive,
            Sign::Zero => Sign::Zero,
            Sign::Positive => Sign::Negative,
        }
    }
}

fn c3(p: &Point) -> robust::Coord3D<f64> {
    robust::Coord3D {
        x: p[0],
        y: p[1],
        z: p[2],
    }
}

/// Sign of `dot(b-a, cross(c-a, d-a))`; positive for a positively oriented tetrahedron.
pub fn orient3d(a: &Point, b: &Point, c: &Point, d: &Point) -> Sign {
    Sign::of(-robust::orient3d(c3(a), c3(b), c3(c), c3(d)))
}

/// For positively oriented `(a,b,c,d)`: positive when `e` is strictly inside their circumsphere.
pub fn insphere(a: &Point, b: &Point, c: &Point, d: &Point, e: &Point) -> Sign {
    Sign::of(-robust::insphere(c3(a), c3(b), c3(c), c3(d), c3(e)))
}
