//! Mesh criteria and sizing fields (DESIGN.md layer 4; Rineau's thesis §3.2.2 and §3.4, with
//! the meaning CGAL Mesh_3 gives its criteria, so that the same numbers mean the same mesh).
//!
//! Facets (restricted facets of the surface, each with its surface Delaunay ball):
//! - angle: lower bound on the smallest angle of the facet, in degrees;
//! - size: upper bound on the radius of the surface Delaunay ball;
//! - distance: upper bound on the distance from the facet's circumcenter to the center of
//!   its surface Delaunay ball (an approximation of the distance to the surface);
//! - topology: every vertex of a restricted facet lies on the surface (rule R1).
//!
//! Cells (tetrahedra whose circumcenter lies in a subdomain):
//! - radius-edge ratio: upper bound on circumradius / shortest edge;
//! - size: upper bound on the circumradius;
//! - surface slivers: lower bound on the smallest dihedral angle of a cell with at least three
//!   vertices on the surface. Not in the thesis nor in CGAL: such a cell may have a good
//!   radius-edge ratio, and exudation, which keeps the boundary, often cannot remove it (CGAL
//!   moves surface vertices for that, changing the boundary), so refinement treats it as a bad
//!   cell (its circumcenter, or by rule R3.2 the surface facet that circumcenter encroaches).
//!   On by default at 15 degrees.
//!
//! A criterion that was never set is not enforced. Sizes and distances are a constant or a
//! field `size(p, dimension, index)` evaluated at the refinement point (the surface ball's
//! center for facets, the circumcenter for cells): dimension 2 with index
//! `(low << 16) | high` of the two labels the surface separates, dimension 3 with the
//! subdomain label.
//!
//! Invariants (held by the setters): angle in `(0, 30]`; ratio finite and `>= 2`; constant
//! sizes and distances finite and positive; surface sliver angle in `[0, 20]` (0: off). The
//! thesis proves termination for larger ratio bounds only (Th. 3.5.5: `ratio >= 4 / (1 - 5g)`,
//! `g >= 0.03`); 30 degrees and 2 are the usual practical limits of Delaunay refinement, beyond
//! which it may not terminate. No proof covers the surface sliver bound; 20 degrees is the
//! largest value accepted, and the default 15 is the largest value measured (it terminated on
//! every shape of the C tests).

use crate::error::{Error, ErrorKind, Result};
use crate::geometry::{cross, dist2, dot, sub, triangle_circumcenter};
use crate::predicates::Point;

/// A sizing field: `(point, dimension, index) -> size`; a result that is not a positive
/// finite number is a failure of the callback.
pub type SizingFn = Box<dyn Fn(&Point, i32, i32) -> f64>;

/// A size or distance bound.
pub enum Size {
    Constant(f64),
    Field(SizingFn),
}

impl Size {
    fn at(&self, p: &Point, dimension: i32, index: i32, what: &str) -> Result<f64> {
        match self {
            Size::Constant(v) => Ok(*v),
            Size::Field(f) => {
                let v = f(p, dimension, index);
                if v.is_finite() && v > 0.0 {
                    Ok(v)
                } else {
                    Err(Error::new(
                        ErrorKind::Callback,
                        format!(
                            "the {what} sizing field returned {v} at {p:?} (dimension \
                             {dimension}, index {index}): sizes must be positive and finite"
                        ),
                    ))
                }
            }
        }
    }
}

/// Which bound a sizing field replaces (`delmesh_mesher_set_sizing_field`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Which {
    FacetSize,
    FacetDistance,
    CellSize,
}

/// How far an element is from meeting the criteria: the class (a topology failure before a
/// shape or size failure) and the worst ratio of a measure to its bound (> 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Badness {
    pub class: u8,
    pub ratio: f64,
}

/// Default of [`Criteria::set_surface_sliver_angle`], degrees.
pub const DEFAULT_SURFACE_SLIVER_ANGLE: f64 = 15.0;

/// Class of a facet with a vertex off the surface (rule R1).
pub const TOPOLOGY: u8 = 1;
/// Class of an element that fails a shape, size or distance bound.
pub const SHAPE_OR_SIZE: u8 = 0;

#[derive(Default)]
pub struct Criteria {
    /// sin² of the facet angle bound.
    facet_angle_sin2: Option<f64>,
    facet_size: Option<Size>,
    facet_distance: Option<Size>,
    facet_topology: bool,
    /// Square of the radius-edge bound.
    cell_ratio2: Option<f64>,
    cell_size: Option<Size>,
    /// Smallest dihedral angle (degrees) of a cell with three or four vertices on the surface.
    surface_sliver_angle: Option<f64>,
}

impl Criteria {
    /// No bound set but two: facet topology (vertices on the surface), as in CGAL, and
    /// surface slivers below [`DEFAULT_SURFACE_SLIVER_ANGLE`].
    pub fn new() -> Self {
        Criteria {
            facet_topology: true,
            surface_sliver_angle: Some(DEFAULT_SURFACE_SLIVER_ANGLE),
            ..Criteria::default()
        }
    }

    /// Lower bound (degrees, in `[0, 20]`; 0 turns it off) on the smallest dihedral angle of
    /// the cells with at least three vertices on the surface.
    pub fn set_surface_sliver_angle(&mut self, degrees: f64) -> Result<()> {
        if !(0.0..=20.0).contains(&degrees) {
            return Err(Error::invalid_argument(format!(
                "surface sliver angle {degrees} must lie in [0, 20] degrees (0: off): larger \
                 bounds are not known to terminate"
            )));
        }
        self.surface_sliver_angle = (degrees > 0.0).then_some(degrees);
        Ok(())
    }

    /// The badness of a cell with at least three vertices on the surface, as a surface sliver.
    pub fn surface_sliver(&self, tet: [&Point; 4]) -> Option<Badness> {
        let bound = self.surface_sliver_angle?;
        let angle = crate::quality::min_dihedral(tet.map(|p| *p));
        (angle < bound).then(|| Badness {
            class: SHAPE_OR_SIZE,
            ratio: bound / angle.max(f64::MIN_POSITIVE),
        })
    }

    pub fn set_facet_angle(&mut self, degrees: f64) -> Result<()> {
        if !(degrees > 0.0 && degrees <= 30.0) {
            return Err(Error::invalid_argument(format!(
                "facet angle {degrees} must lie in (0, 30] degrees: above 30 the surface \
                 refinement is not guaranteed to terminate"
            )));
        }
        self.facet_angle_sin2 = Some(degrees.to_radians().sin().powi(2));
        Ok(())
    }

    pub fn set_facet_size(&mut self, size: f64) -> Result<()> {
        self.facet_size = Some(Size::Constant(positive("facet size", size)?));
        Ok(())
    }

    pub fn set_facet_distance(&mut self, distance: f64) -> Result<()> {
        self.facet_distance = Some(Size::Constant(positive("facet distance", distance)?));
        Ok(())
    }

    pub fn set_facet_topology(&mut self, vertices_on_surface: bool) {
        self.facet_topology = vertices_on_surface;
    }

    pub fn set_cell_radius_edge_ratio(&mut self, ratio: f64) -> Result<()> {
        if !(ratio.is_finite() && ratio >= 2.0) {
            return Err(Error::invalid_argument(format!(
                "cell radius-edge ratio {ratio} must be finite and at least 2: below 2 the \
                 volume refinement is not guaranteed to terminate"
            )));
        }
        self.cell_ratio2 = Some(ratio * ratio);
        Ok(())
    }

    pub fn set_cell_size(&mut self, size: f64) -> Result<()> {
        self.cell_size = Some(Size::Constant(positive("cell size", size)?));
        Ok(())
    }

    pub fn set_sizing_field(&mut self, which: Which, f: SizingFn) {
        let slot = match which {
            Which::FacetSize => &mut self.facet_size,
            Which::FacetDistance => &mut self.facet_distance,
            Which::CellSize => &mut self.cell_size,
        };
        *slot = Some(Size::Field(f));
    }

    /// The spacing at which a dual segment is sampled for crossings its ends do not show:
    /// the facet size near `p`, or infinite when no facet size is set.
    pub fn sampling_step(&self, p: &Point, labels: (i32, i32)) -> Result<f64> {
        match &self.facet_size {
            None => Ok(f64::INFINITY),
            Some(s) => s.at(p, 2, patch_index(labels), "facet size"),
        }
    }

    /// The badness of a restricted facet `tri` whose surface Delaunay ball has center
    /// `center`, squared radius `radius2`, and separates `labels`; `on_surface` tells
    /// whether all three vertices are surface points. `None` when it meets every criterion.
    pub fn facet(
        &self,
        tri: [&Point; 3],
        center: &Point,
        radius2: f64,
        labels: (i32, i32),
        on_surface: bool,
    ) -> Result<Option<Badness>> {
        if self.facet_topology && !on_surface {
            return Ok(Some(Badness {
                class: TOPOLOGY,
                ratio: f64::INFINITY,
            }));
        }
        let index = patch_index(labels);
        let mut worst = 0.0f64;
        if let Some(bound) = self.facet_angle_sin2 {
            worst = worst.max(bound / min_angle_sin2(tri));
        }
        if let Some(s) = &self.facet_size {
            let s = s.at(center, 2, index, "facet size")?;
            worst = worst.max(radius2 / (s * s));
        }
        if let Some(d) = &self.facet_distance {
            let d = d.at(center, 2, index, "facet distance")?;
            let c = triangle_circumcenter(tri);
            worst = worst.max(dist2(&c, center) / (d * d));
        }
        Ok(bad(worst))
    }

    /// Whether a cell meets the radius-edge bound (when set).
    pub fn cell_shape_holds(&self, tet: [&Point; 4], center: &Point) -> bool {
        let Some(bound2) = self.cell_ratio2 else {
            return true;
        };
        let shortest2 = (0..4)
            .flat_map(|i| (i + 1..4).map(move |j| (i, j)))
            .map(|(i, j)| dist2(tet[i], tet[j]))
            .fold(f64::INFINITY, f64::min);
        dist2(center, tet[0]) / shortest2 <= bound2
    }

    /// The badness of a cell `tet` with circumcenter `center` in subdomain `label`.
    pub fn cell(&self, tet: [&Point; 4], center: &Point, label: i32) -> Result<Option<Badness>> {
        let radius2 = dist2(center, tet[0]);
        let mut worst = 0.0f64;
        if let Some(bound2) = self.cell_ratio2 {
            let shortest2 = (0..4)
                .flat_map(|i| (i + 1..4).map(move |j| (i, j)))
                .map(|(i, j)| dist2(tet[i], tet[j]))
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(radius2 / shortest2 / bound2);
        }
        if let Some(s) = &self.cell_size {
            let s = s.at(center, 3, label, "cell size")?;
            worst = worst.max(radius2 / (s * s));
        }
        Ok(bad(worst))
    }
}

fn bad(ratio: f64) -> Option<Badness> {
    // NaN (a degenerate construction) counts as bad: refining it is the safe side.
    (ratio > 1.0 || ratio.is_nan()).then_some(Badness {
        class: SHAPE_OR_SIZE,
        ratio: if ratio.is_nan() { f64::MAX } else { ratio },
    })
}

fn positive(what: &str, v: f64) -> Result<f64> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(Error::invalid_argument(format!(
            "{what} {v} must be positive and finite"
        )))
    }
}

/// The sizing-field index of the surface between two labels.
pub fn patch_index(labels: (i32, i32)) -> i32 {
    let (lo, hi) = (labels.0.min(labels.1), labels.0.max(labels.1));
    lo.wrapping_shl(16) | (hi & 0xffff)
}

/// sin² of the smallest angle of a triangle: the angle opposite the shortest edge, whose
/// sine is twice the area over the product of the two other edges.
pub fn min_angle_sin2(t: [&Point; 3]) -> f64 {
    let e = [dist2(t[1], t[2]), dist2(t[2], t[0]), dist2(t[0], t[1])];
    let w = cross(&sub(t[1], t[0]), &sub(t[2], t[0]));
    let shortest = (0..3).fold(0, |m, k| if e[k] < e[m] { k } else { m });
    let others = e[(shortest + 1) % 3] * e[(shortest + 2) % 3];
    dot(&w, &w) / others
}
