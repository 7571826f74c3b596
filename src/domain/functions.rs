//! Domains given by a function of the point: an implicit function (negative inside: one
//! subdomain, label 1) or a labeling function (any number of subdomains and the interfaces
//! between them), e.g. the C callbacks of `delmesh_domain_new_implicit` and
//! `delmesh_domain_new_labeled`.

use super::{BBox, Domain};
use crate::error::{Error, ErrorKind, Result};
use crate::predicates::Point;

/// The user's function.
pub enum Oracle {
    /// `f(p) < 0` inside (label 1), `>= 0` outside; NaN is a failure.
    Implicit(Box<dyn Fn(&Point) -> f64>),
    /// The label of `p`: 0 outside, > 0 a subdomain; negative is a failure.
    Labels(Box<dyn Fn(&Point) -> i32>),
}

/// A domain known through a function (see the module documentation).
pub struct FunctionDomain {
    oracle: Oracle,
    bbox: BBox,
    error_bound: f64,
    seeds: Vec<Point>,
}

impl FunctionDomain {
    /// `relative_error` bounds the distance of surface points to the surface, relative to
    /// the box diagonal; it must lie in `(0, 0.1]`.
    pub fn new(oracle: Oracle, bbox: BBox, relative_error: f64) -> Result<Self> {
        if !(relative_error > 0.0 && relative_error <= 0.1) {
            return Err(Error::invalid_argument(format!(
                "relative_error = {relative_error} must lie in (0, 0.1]"
            )));
        }
        // Below about 1e-15 relative, bisection stops at adjacent doubles anyway.
        let error_bound = relative_error.max(1e-15) * bbox.diagonal();
        Ok(FunctionDomain {
            oracle,
            bbox,
            error_bound,
            seeds: Vec::new(),
        })
    }

    /// Adds user points on the surface; each must be finite and inside the box.
    pub fn add_seeds(&mut self, points: &[Point]) -> Result<()> {
        if let Some(i) = points.iter().position(|p| !self.bbox.contains(p)) {
            return Err(Error::invalid_input(format!(
                "surface point {i} {:?} is not a finite point inside the bbox {:?}..{:?}",
                points[i], self.bbox.lo, self.bbox.hi
            )));
        }
        self.seeds.extend_from_slice(points);
        Ok(())
    }
}

impl Domain for FunctionDomain {
    fn classify(&self, p: &Point) -> Result<i32> {
        match &self.oracle {
            Oracle::Implicit(f) => {
                let v = f(p);
                if v.is_nan() {
                    Err(callback_error(format!(
                        "the implicit function returned NaN at {p:?}"
                    )))
                } else {
                    Ok(i32::from(v < 0.0))
                }
            }
            Oracle::Labels(f) => {
                let l = f(p);
                if l < 0 {
                    Err(callback_error(format!(
                        "the labeling function returned {l} at {p:?}"
                    )))
                } else {
                    Ok(l)
                }
            }
        }
    }

    fn bbox(&self) -> &BBox {
        &self.bbox
    }

    fn error_bound(&self) -> f64 {
        self.error_bound
    }

    fn seeds(&self) -> &[Point] {
        &self.seeds
    }
}

fn callback_error(message: String) -> Error {
    Error::new(ErrorKind::Callback, message)
}
