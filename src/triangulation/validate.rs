//! Exact consistency check of a triangulation, for tests and fuzzers.

use super::insert::Located;
use super::tets::{FACE, INFINITE};
use super::{PointState, Triangulation};
use crate::predicates::Sign;

impl Triangulation<'_> {
    /// Checks every invariant of the module documentation exactly; the error names the first
    /// tetrahedron, facet or point that breaks one. Cost: a few predicates per tetrahedron, and
    /// one walk per hidden point.
    pub fn validate(&mut self) -> Result<(), String> {
        let mut used = vec![false; self.points.len()];
        for t in self.tets.live().collect::<Vec<_>>() {
            self.check_tetrahedron(t)?;
            for v in self.tets.vertices(t) {
                if v != INFINITE {
                    used[self.input_index(v) as usize] = true;
                }
            }
        }
        self.check_free_list()?;
        for (v, s) in self.state.iter().enumerate() {
            let i = self.order[v] as usize;
            let ok = match s {
                PointState::Pending => false,
                PointState::Inserted => used[i] || self.is_regular(),
                PointState::Duplicate(w) => !used[i] && self.input[*w as usize] == self.input[i],
                PointState::Hidden => !used[i] && self.is_regular(),
                PointState::Removed => !used[i],
            };
            if !ok {
                return Err(format!("point {i} is {s:?} but used = {}", used[i]));
            }
        }
        self.check_hidden(&used)
    }

    fn check_tetrahedron(&self, t: u32) -> Result<(), String> {
        let v = self.tets.vertices(t);
        let infinite = v.iter().filter(|&&x| x == INFINITE).count();
        let distinct = (0..4).all(|i| (i + 1..4).all(|j| v[i] != v[j]));
        if infinite > 1
            || !distinct
            || v.iter()
                .any(|&x| x != INFINITE && x as usize >= self.points.len())
        {
            return Err(format!("tetrahedron {t} has vertices {v:?}"));
        }
        if infinite == 0 {
            let [a, b, c, d] = v.map(|x| self.point(x));
            if crate::predicates::orient3d(a, b, c, d) != Sign::Positive {
                return Err(format!("tetrahedron {t} {v:?} is not positively oriented"));
            }
        }
        for i in 0..4 {
            self.check_facet(t, i)?;
        }
        Ok(())
    }

    /// Facet `i` of `t`: glued symmetrically to a live tetrahedron with the same three
    /// vertices, and the vertex opposite across it is not in conflict with `t`.
    fn check_facet(&self, t: u32, i: usize) -> Result<(), String> {
        let facet = self.tets.glued(t, i);
        let (u, j) = (facet >> 2, (facet & 3) as usize);
        if u as usize >= self.tets.slots() || !self.tets.is_live(u) {
            return Err(format!("facet {i} of tetrahedron {t} is glued to dead {u}"));
        }
        if self.tets.glued(u, j) != 4 * t + i as u32 {
            return Err(format!(
                "facet {i} of tetrahedron {t} is glued one way only"
            ));
        }
        let mut mine = FACE[i].map(|k| self.tets.vertices(t)[k]);
        let mut theirs = FACE[j].map(|k| self.tets.vertices(u)[k]);
        mine.sort_unstable();
        theirs.sort_unstable();
        if mine != theirs {
            return Err(format!(
                "tetrahedra {t} and {u} are glued along different facets"
            ));
        }
        let opposite = self.tets.vertices(u)[j];
        if opposite != INFINITE && self.in_conflict(t, opposite) {
            return Err(format!(
                "tetrahedron {t} is in conflict with vertex {opposite} of its neighbour {u}"
            ));
        }
        if opposite == INFINITE && self.tets.infinite_position(t).is_none() {
            // The hull facet must face away from t: its outer side is where t is not.
            let q = *self.point(self.tets.vertices(t)[i]);
            let k = self.tets.infinite_position(u).unwrap_or(0);
            if self.orient_with(u, k, &q) != Sign::Negative {
                return Err(format!("hull tetrahedron {u} is not oriented outward"));
            }
        }
        Ok(())
    }

    fn check_free_list(&self) -> Result<(), String> {
        match self.tets.free.iter().find(|&&t| self.tets.is_live(t)) {
            Some(t) => Err(format!("free tetrahedron {t} is live")),
            None => Ok(()),
        }
    }

    /// Every hidden weighted point is still hidden: the tetrahedron containing it is not in
    /// conflict with it (then none is).
    fn check_hidden(&mut self, used: &[bool]) -> Result<(), String> {
        if !self.is_regular() {
            return Ok(());
        }
        for v in 0..self.points.len() as u32 {
            let i = self.input_index(v);
            let not_hidden = matches!(
                self.state[v as usize],
                PointState::Duplicate(_) | PointState::Removed
            );
            if used[i as usize] || not_hidden {
                continue;
            }
            match self.locate(v) {
                Ok(Located::Hidden) => {}
                _ => {
                    return Err(format!(
                        "hidden point {i} is in conflict with the triangulation"
                    ))
                }
            }
        }
        Ok(())
    }
}
