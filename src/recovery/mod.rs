//! Tetrahedralization of a triangulated surface that keeps every input triangle as a facet
//! (George and Borouchaki, INRIA RR-4397, 2002, §5).
//!
//! Pipeline:
//! 1. [`validate`]: the input is checked before anything else (finite coordinates, indices,
//!    degenerate and duplicate triangles, edges with a single triangle); self-intersections
//!    are looked for before the first point is added on the surface, among the triangles that
//!    are not facets yet, or when meshing fails (`IntersectionCheck`): a surface whose
//!    triangles are all facets of a tetrahedralization does not intersect itself.
//! 2. The Delaunay triangulation of the surface vertices, of the vertices no triangle uses
//!    that can be meshed ([`validate::isolated_vertices`], TetGen's `.node` semantics), and
//!    of the corners of an enlarged bounding box (§5.1), so that no input triangle lies on the
//!    convex hull.
//! 3. Missing edges, then missing triangles, are recovered (§5.2), by flips and by points
//!    added on the surface, exactly on it for the orientation tests ([`steiner`]); with
//!    `keep_convex_hull`, the convex hull's triangles ([`hull`]) too, and points added on
//!    those alone stay there (with their rounded coordinates).
//!    Where that fails (a `Limit` error), the whole is tried again with, for each sub-edge
//!    flips leave missing, a point inside the volume first ([`interior`]), then once more
//!    with shells of edges crossed in a segment's plane shrunk first; last, with the
//!    subfaces around every point added on the surface made Delaunay in their triangle
//!    ([`ATTEMPTS`]). Up to their first point, attempts that shrink shells alike do the
//!    same: that start is made once ([`Start`]). The flip passes before points are added
//!    follow a schedule; where the first run's mesh has interior points, the other runs are
//!    made too: three schedules with the missing sub-edges in the partition's order, the
//!    same in the reverse order ([`EdgeOrder`]), then one under TetGen's rule for flips in
//!    both orders, and the fewest points win ([`RUNS`]); a schedule that begins with passes
//!    an earlier one made in the same order goes on from a copy of the state they left
//!    ([`Prefix`]).
//! 4. Points added on the surface are moved off it, then merged away, or removed where their
//!    star, or their star and a few layers around it, can be filled again without them by
//!    this same recovery with no point allowed (§5.3, [`suppress`]), or two neighbouring
//!    points merged into one; where points are left inside the kept regions, once more with
//!    more layers, which may then hold another point ([`suppress::SECOND_REMOVAL`]). Points
//!    outside the kept regions are left alone.
//! 5. Regions are found by flood fill from the box across non-input facets; the box region
//!    is dropped (§5.3, last remark).
//! 6. Optional quality refinement with interior points only ([`refine`]: radius-edge and
//!    volume bounds, TetGen's `-q`/`-a` with `-Y`).
//! 7. Flips that raise the worst shape ([`flips::improve_by_flips`]): with a radius-edge
//!    bound, of every tetrahedron worse than half a regular one (a new tetrahedron stays
//!    above the bound only with three or four surface vertices); without, of the nearly flat
//!    ones, never raising the worst radius-edge ratio. A cap (shaped worse than half a
//!    regular tetrahedron, radius-edge ratio 100 or more) no flip of its own edges and facets
//!    removes goes, where that is better, through the recovery of an edge from one of its
//!    corners to a vertex nearby (§5.2's flips, undone otherwise).
//! 8. With a ratio bound, the flat tetrahedra left far above it with an input facet (a wedge
//!    between two input triangles that meet at a nearly flat angle, a sliver on one) or with
//!    three or four vertices on the surface (which the flips may leave so) have an edge split
//!    by an interior point ([`wedges`]), and the new tetrahedra above the bound are refined;
//!    then the flips of step 7 on what the splits and that refinement made (with the bound
//!    1.414: pinion's largest ratio 308 -> 255, armadillo's tetrahedra below 5 degrees 638 ->
//!    608).
//! 9. With a ratio bound, the interior points of the tetrahedra with a dihedral angle below 15
//!    degrees move where the worst shape of their balls is best ([`smooth`], TetGen's
//!    smoothing), and the flips of step 7 follow on the balls that changed (bunny00's
//!    tetrahedra below 15 degrees 432 -> 223).
//!
//! Invariants of the result: every input triangle is a facet of the output with the same
//! vertex indices; no vertex is added on the input surface; output vertices are the input
//! vertices in input order followed by the Steiner points, all strictly inside a region; an
//! input vertex no triangle uses is a vertex of the mesh exactly when it lies inside a kept
//! region.

mod bvh;
mod by_vertex;
mod classify;
pub mod edges;
pub mod faces;
pub mod flips;
mod hull;
pub mod interior;
pub mod partition;
mod refine;
mod smooth;
pub mod steiner;
pub mod suppress;
pub mod tetmesh;
pub mod validate;
mod wedges;

use rustc_hash::FxHashSet as HashSet;

use crate::error::{Error, ErrorKind, Result};
use crate::mesh::Mesh;
use crate::predicates::Point;
use edges::{
    Guard::{self, Clear, Eligible, Open},
    DEEPEST, DEPTH,
};
use partition::Partition;
use tetmesh::{EdgeOrder, TetMesh};

/// A region seed (TetGen `.poly` semantics): the region containing `point` gets `label`
/// and, when `max_volume > 0`, that bound on its tetrahedra's volumes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegionSeed {
    pub point: [f64; 3],
    pub label: i32,
    pub max_volume: f64,
}

/// A triangulated surface with its region and hole seeds, as the readers return it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Surface {
    /// x y z interleaved.
    pub xyz: Vec<f64>,
    /// Three vertex indices (0-based) per triangle.
    pub triangles: Vec<u32>,
    pub regions: Vec<RegionSeed>,
    /// The region containing each hole seed is removed.
    pub holes: Vec<[f64; 3]>,
}

/// What [`tetrahedralize_surface`] does besides recovering the surface.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SurfaceOptions {
    /// 0 = no quality refinement; else cells whose radius-edge ratio is above it are refined
    /// with interior points, never splitting an input triangle.
    pub max_radius_edge_ratio: f64,
    /// 0 = none; else an upper bound on every tetrahedron's volume.
    pub max_volume: f64,
    /// Keep the tetrahedra of the convex hull outside the surface (label 0 is never given:
    /// they get their own region label).
    pub keep_convex_hull: bool,
    pub regions: Vec<RegionSeed>,
    pub holes: Vec<[f64; 3]>,
}

/// Tetrahedralizes the regions that `triangles` (3 indices per triangle into `xyz`, 3
/// coordinates per vertex) enclose, keeping every triangle as a facet.
pub fn tetrahedralize_surface(
    xyz: &[f64],
    triangles: &[u32],
    options: &SurfaceOptions,
) -> Result<Mesh> {
    let (points, rest) = xyz.as_chunks::<3>();
    let (tris, trest) = triangles.as_chunks::<3>();
    if !rest.is_empty() || !trest.is_empty() {
        return Err(Error::invalid_input(
            "coordinates or triangle indices are not a multiple of 3",
        ));
    }
    validate::check_surface_but_intersections(points, tris)?;
    check_options(options)?;
    let isolated = validate::isolated_vertices(points, tris);
    // With the convex hull kept, its triangles are recovered and bound regions as the input's.
    let mut bounding = tris.to_vec();
    if options.keep_convex_hull {
        let mut vertices: Vec<u32> = tris.iter().flatten().chain(&isolated).copied().collect();
        vertices.sort_unstable();
        vertices.dedup();
        bounding.extend(hull::triangles(points, tris, &vertices)?);
    }
    let mut intersections = IntersectionCheck {
        points,
        triangles: tris,
        done: false,
    };
    let input = Input {
        points,
        bounding: &bounding,
        first_hull: tris.len(),
        isolated: &isolated,
        options,
        edge_order: EdgeOrder::Partition,
    };
    // The first run's error is the one reported; where it needs points, the other runs are
    // made too, and the fewest points win (the first among equals).
    let mut starts = [Starts::default(), Starts::default()];
    let mut run = |k: usize| {
        let (order, schedule) = RUNS[k];
        let input = Input {
            edge_order: order,
            ..input
        };
        // The copies each order keeps for its later runs.
        let starts = &mut starts[usize::from(order == EdgeOrder::Reversed)];
        starts.later = (RUNS[k + 1..].iter())
            .filter(|(o, _)| *o == order)
            .map(|&(_, s)| s)
            .collect();
        recover(&input, &mut intersections, starts, schedule)
    };
    let mut best = run(0);
    for k in 1..RUNS.len() {
        let fewest = match &best {
            Ok(b) if !b.kept.is_empty() => b.kept.len(),
            _ => break,
        };
        match run(k) {
            Ok(other) if other.kept.len() < fewest => best = Ok(other),
            _ => {}
        }
    }
    // The kept copies are freed before refinement.
    drop(starts);
    match best {
        Ok(recovered) => complete(recovered, points, tris, options),
        // A self-intersection is the first cause to report.
        Err(e) => intersections.run().and(Err(e)),
    }
}

/// What recovery works on: the input's points, the triangles to recover (the input's, then
/// from `first_hull` on the convex hull's with `keep_convex_hull`) and the vertices no
/// triangle uses that are meshed.
#[derive(Clone, Copy)]
struct Input<'a> {
    points: &'a [Point],
    bounding: &'a [[u32; 3]],
    first_hull: usize,
    isolated: &'a [u32],
    options: &'a SurfaceOptions,
    edge_order: EdgeOrder,
}

/// A mesh of the box in which every triangle of [`Input::bounding`] is a facet and no point
/// is on it, with its partition and regions; `kept` are the points beyond the input's in
/// the kept regions, in order.
struct Recovered {
    mesh: TetMesh,
    part: Partition,
    regions: classify::Regions,
    kept: Vec<u32>,
}

/// The passes of [`Progress::by_flips`] over the sub-edges flips leave missing: the depth of
/// each pass's edge removals and whether they are guarded ([`edges::recover_edge`]).
type Schedule = &'static [(u32, Guard)];

/// Guarded passes, deeper and deeper. Where the unguarded search at [`edges::DEPTH`] leaves
/// sub-edges missing, a guarded one at that depth recovers as many as the deeper unguarded
/// ones, in a fraction of their time (fandisk: 5 left, 4 after either, in 3 ms against 34
/// ms), so the first run takes it first.
const GUARDED: Schedule = &[
    (DEPTH, Open),
    (DEPTH, Clear),
    (DEPTH + 1, Clear),
    (DEEPEST, Clear),
];
/// Unguarded passes down to the deepest, then a guarded one.
const OPEN: Schedule = &[
    (DEPTH, Open),
    (DEPTH + 1, Open),
    (DEEPEST, Open),
    (DEEPEST, Clear),
];
/// A guarded pass, then the deepest.
const SHORT: Schedule = &[(DEPTH, Open), (DEPTH, Clear), (DEEPEST, Clear)];
/// TetGen's way: its rule from the first pass ([`edges::Eligible`]), at [`edges::DEPTH`] then
/// a level deeper. Measured against it (debug driver, one run each, two at a time): with a
/// pass at [`edges::DEEPEST`] after those, the same star-shaped surfaces, Chazelle's
/// polyhedron with three notches a side 11 points instead of 10, anchor 10.2 s instead of 8.8;
/// at [`edges::DEPTH`] alone, 11 points on the star-shaped surfaces instead of 10, Chazelle 11,
/// pipe 4 instead of 5 in a worse-shaped mesh (largest radius-edge ratio 121 instead of 22
/// without a bound, 431 with 1.414); after the unguarded pass, 13 on the star-shaped surfaces,
/// Chazelle's polyhedron with four notches a side 14 instead of 15 but with three 11.
const ELIGIBLE: Schedule = &[(DEPTH, Eligible), (DEPTH + 1, Eligible)];

/// The runs of recovery, each a schedule with the sub-edges in the partition's order or in
/// the reverse order ([`EdgeOrder`]): the first always, the others where it leaves interior
/// points, and the fewest points win (the first among equals). Which run needs the fewest
/// varies from input to input (a sub-edge recovered by other flips changes where every later
/// point goes). Interior points with each of the first six in turn: anchor 11 / 10 / 11, 8 /
/// 8 / 9; joint 1 / 1 / 1, 3 / 4 / 3; handle 2 / 2 / 1, 1 / 0; pipe 5 / 6 / 5, 7 / 6 / 6;
/// Chazelle's polyhedra with two to eight notches a side 6 / 5 / 6, 6 / 6 / 6; 13 / 11 / 12,
/// 14 / 13 / 12; 17 / 20 / 17, 17 / 16 / 15; 23 / 26 / 21, 25 / 24 / 26; 29 / 29 / 27, 37 /
/// 35 / 38; 31 / 40 / 37, 36 / 41 / 36; 50 / 46 / 53, 46 / 48 / 42 (TetGen 24, 3, 0, 18, 6,
/// 8, 14 and 20 with points on its boundary too from three notches, none from six: it
/// fails). The last two, under TetGen's rule, take Chazelle's polyhedra with three and eight
/// notches a side to 10 and 38 points and the star-shaped surfaces of the tests from 14
/// points on 11 of 52 to 10 on 8; on anchor, joint, handle, pipe and Chazelle's with two and
/// four to seven notches they do no better.
static RUNS: [(EdgeOrder, Schedule); 8] = [
    (EdgeOrder::Partition, GUARDED),
    (EdgeOrder::Partition, OPEN),
    (EdgeOrder::Partition, SHORT),
    (EdgeOrder::Reversed, GUARDED),
    (EdgeOrder::Reversed, OPEN),
    (EdgeOrder::Reversed, SHORT),
    (EdgeOrder::Partition, ELIGIBLE),
    (EdgeOrder::Reversed, ELIGIBLE),
];

/// The schedule of [`fill_without_points`].
const FILL: Schedule = &[(DEPTH, Open), (DEPTH, Clear)];

/// Recovery with `schedule` by the attempts in order, while they stop at a limit; the first
/// one's error is the one reported when all do.
fn recover(
    input: &Input,
    intersections: &mut IntersectionCheck,
    starts: &mut Starts,
    schedule: Schedule,
) -> Result<Recovered> {
    let mut attempt = recover_by(input, intersections, starts, ATTEMPTS[0], schedule);
    for &next in &ATTEMPTS[1..] {
        if !matches!(&attempt, Err(e) if e.kind == ErrorKind::Limit) {
            break;
        }
        match recover_by(input, intersections, starts, next, schedule) {
            Err(e) if e.kind == ErrorKind::Limit => {}
            other => attempt = other,
        }
    }
    attempt
}

/// How an attempt recovers what flips leave missing.
#[derive(Clone, Copy, Debug)]
struct Attempt {
    /// A point inside the volume first for each sub-edge flips leave missing ([`interior`]),
    /// before any on the surface.
    interior: bool,
    /// An edge crossed in its plane is removed after its shell is shrunk where it cannot be
    /// at once ([`edges::recover_edge`]).
    shrink: bool,
    /// The subfaces around each point added on the surface are made Delaunay in their input
    /// triangle ([`Partition::delaunay_around`]).
    delaunay: bool,
    /// The attempt stops at a quarter as many points as triangles ([`Attempt::budget`]).
    short: bool,
}

impl Attempt {
    /// How many points the attempt may add for `triangles` triangles to recover. Two per
    /// triangle, far more than any input that meshes needs (26 for 980 triangles at most in
    /// the C test), so that an attempt that goes astray stops soon. The middle attempts, with
    /// points inside first, follow a failure: a quarter as many points as triangles (anchor
    /// meshes well within it), so that an input they cannot mesh either fails in seconds.
    /// The last has the whole budget again: Chazelle's polyhedron with five notches a side
    /// (268 triangles) meshes so, with 137 points added (the quarter is 131); with the
    /// quarter it stopped.
    fn budget(self, triangles: usize) -> usize {
        if self.short {
            triangles / 4 + 64
        } else {
            2 * triangles + 64
        }
    }
}

/// Points on the surface alone first; where they cannot do it, points inside the volume
/// first; then also coplanar crossings taken away after shrinking their shells (Chazelle's
/// polyhedron with three notches a side meshes so). Last,
/// points on the surface again, then inside first, with Delaunay subfaces: where the
/// surface is planar over several triangles, the split subfaces of the first attempts grow
/// thin, and points added on them a rounding apart defeat recovery (Chazelle's polyhedron
/// with four notches meshes so). Not first: on anchor, points on the surface with Delaunay
/// subfaces run out of budget before points inside succeed, and the terrain keeps a point
/// the first attempt does without.
const ATTEMPTS: [Attempt; 5] = [
    Attempt {
        interior: false,
        shrink: false,
        delaunay: false,
        short: false,
    },
    Attempt {
        interior: true,
        shrink: false,
        delaunay: false,
        short: true,
    },
    Attempt {
        interior: true,
        shrink: true,
        delaunay: false,
        short: true,
    },
    Attempt {
        interior: false,
        shrink: false,
        delaunay: true,
        short: false,
    },
    Attempt {
        interior: true,
        shrink: false,
        delaunay: true,
        short: false,
    },
];

impl Input<'_> {
    /// The first point added after the input's and the box's eight corners.
    fn first_added(&self) -> u32 {
        self.points.len() as u32 + 8
    }
}

/// The self-intersection check of the input, run at most once: when recovery is about to add
/// its first point on the surface, or when meshing fails. Until then the mesh is a
/// tetrahedralization of the input vertices, and two of its facets meet only along their
/// shared vertices and edge: the input triangles that are facets cannot intersect one
/// another, and only the pairs with a triangle that is not are tested
/// ([`validate::check_intersections_of`]). An input recovered with no point is thus never
/// searched for intersections: most inputs are such, and the search took a quarter of
/// their time.
struct IntersectionCheck<'a> {
    points: &'a [Point],
    triangles: &'a [[u32; 3]],
    done: bool,
}

impl IntersectionCheck<'_> {
    /// Checks every pair of input triangles.
    fn run(&mut self) -> Result<()> {
        self.run_on(None)
    }

    /// Checks the pairs with an input triangle among `suspects` (numbers among the recovered
    /// triangles: those past the input's, the convex hull's, are left out), or every pair for
    /// `None`.
    fn run_on(&mut self, suspects: Option<&[usize]>) -> Result<()> {
        if std::mem::replace(&mut self.done, true) {
            return Ok(());
        }
        let Some(suspects) = suspects else {
            return validate::check_intersections(self.points, self.triangles);
        };
        let input: Vec<usize> = suspects
            .iter()
            .copied()
            .filter(|&f| f < self.triangles.len())
            .collect();
        validate::check_intersections_of(self.points, self.triangles, &input)
    }
}

/// What every attempt of a schedule with the same `shrink` does first, the same way: the
/// Delaunay triangulation of the surface's vertices in its box, and the flips that recover
/// what they can before any point is added ([`Progress::by_flips`]). Where points are needed
/// (and an attempt may fail), a copy is kept for the next attempts: on anchor, this start
/// took 0.39 s of each attempt's 1 s. The partition is not kept: no point is added before,
/// so it is [`Partition::new`]'s.
#[derive(Clone)]
struct Start {
    shrink: bool,
    mesh: TetMesh,
    /// `None` when every subface was a facet of the Delaunay triangulation.
    progress: Option<(Progress, Missing)>,
}

/// The starts kept for later attempts of the schedule under way ([`Start::of`]), and the
/// states after the first passes of a schedule that a later schedule begins with
/// ([`Prefix`]).
#[derive(Default)]
struct Starts {
    attempts: Vec<Start>,
    prefixes: Vec<Prefix>,
    /// The schedules still to run after the one under way, in the same order.
    later: Vec<Schedule>,
}

/// The state of a start after `passes`, the first passes of a schedule, when sub-edges are
/// still missing and a later schedule begins with the same passes: that one goes on from a
/// copy. The passes are deterministic, so its start is the same as if it made them again
/// (the schedules but [`ELIGIBLE`] begin with the unguarded pass, which took 0.52 s of
/// anchor's 1.4 s start; [`SHORT`] with [`GUARDED`]'s two first passes). [`ELIGIBLE`] starts
/// anew: going on from a copy of the state before any pass made no difference measurable
/// on anchor, pipe, joint and Chazelle's polyhedron with three notches a side (three runs
/// each, alternating: anchor 8.8 to 11.3 s either way).
struct Prefix {
    shrink: bool,
    passes: Schedule,
    mesh: TetMesh,
    progress: Progress,
    stuck: Vec<[u32; 2]>,
}

impl Prefix {
    /// The largest mesh copied (in tetrahedron slots). The copy is made before it is known
    /// whether a later schedule runs, which it does only where the first leaves interior
    /// points, and a copy costs 35 to 50 ns a slot: fandisk (40483 slots, 5 sub-edges
    /// missing after the first pass) and armadillo (178495, 9 missing) end without interior
    /// points, and their two copies took 2 ms each and 6.4 and 7.3 ms, 3 to 4 % of their
    /// time. The inputs that need the later schedules have small meshes where flips fail
    /// (anchor 4270 slots, handle 7844, sphere966 5179).
    const MOST_TETS: usize = 16_384;
}

impl Starts {
    /// The kept state of the longest prefix of `schedule` with `shrink`.
    fn longest(&self, shrink: bool, schedule: Schedule) -> Option<&Prefix> {
        self.prefixes
            .iter()
            .filter(|p| p.shrink == shrink && schedule.starts_with(p.passes))
            .max_by_key(|p| p.passes.len())
    }

    /// The passes of `schedule` from number `done` on, with `shrink`, over the missing
    /// sub-edges `stuck` of `mesh` ([`Progress::edge_passes`]), keeping the states a later
    /// schedule begins with; the sub-edges still missing.
    fn pass_on(
        &mut self,
        mesh: &mut TetMesh,
        part: &Partition,
        progress: &mut Progress,
        mut stuck: Vec<[u32; 2]>,
        (schedule, done, shrink): (Schedule, usize, bool),
    ) -> Result<Vec<[u32; 2]>> {
        for k in done..schedule.len() {
            if stuck.is_empty() {
                break;
            }
            stuck = progress.edge_passes(mesh, part, stuck, &schedule[k..=k], shrink)?;
            self.keep(mesh, progress, &stuck, (shrink, &schedule[..=k]));
        }
        Ok(stuck)
    }

    /// Keeps a copy of the state after `passes`, where sub-edges `stuck` are missing and it
    /// is [`Starts::wanted`].
    fn keep(
        &mut self,
        mesh: &TetMesh,
        progress: &Progress,
        stuck: &[[u32; 2]],
        (shrink, passes): (bool, Schedule),
    ) {
        if !stuck.is_empty() && self.wanted(shrink, passes, mesh.tets.slots()) {
            self.prefixes.push(Prefix {
                shrink,
                passes,
                mesh: mesh.clone(),
                progress: progress.clone(),
                stuck: stuck.to_vec(),
            });
        }
    }

    /// Whether the state after `passes`, the first passes of the schedule under way, in a
    /// mesh of `tets` tetrahedra (slots), is to be kept: a later schedule of the order under
    /// way begins with them, it is not kept yet, and the mesh has at most
    /// [`Prefix::MOST_TETS`] tetrahedra.
    fn wanted(&self, shrink: bool, passes: Schedule, tets: usize) -> bool {
        tets <= Prefix::MOST_TETS
            && self.later.iter().any(|s| s.starts_with(passes))
            && !self
                .prefixes
                .iter()
                .any(|p| p.shrink == shrink && p.passes == passes)
    }
}

impl Start {
    /// The start with `schedule`'s passes, from the longest prefix `starts` keeps; the
    /// states after passes a later schedule shares are kept there.
    fn new(
        input: &Input,
        shrink: bool,
        schedule: Schedule,
        starts: &mut Starts,
    ) -> Result<(Self, Partition)> {
        let part = Partition::new(input.bounding);
        let (mut mesh, begun) = match starts.longest(shrink, schedule) {
            Some(p) => {
                let begun = (p.progress.clone(), p.stuck.clone(), p.passes.len());
                (p.mesh.clone(), Some(begun))
            }
            None => {
                let mut mesh = enclosed_delaunay(input.points, input.bounding, input.isolated)?;
                mesh.edge_order = input.edge_order;
                let begun = Progress::start(&mut mesh, &part).map(|p| {
                    let stuck = p.missing_edges(&part);
                    (p, stuck, 0)
                });
                (mesh, begun)
            }
        };
        let progress = match begun {
            Some((mut p, stuck, done)) => {
                let passes = (schedule, done, shrink);
                let stuck = starts.pass_on(&mut mesh, &part, &mut p, stuck, passes)?;
                let missing = p.faces_after(&mut mesh, &part, stuck)?;
                Some((p, missing))
            }
            None => None,
        };
        let start = Start {
            shrink,
            mesh,
            progress,
        };
        Ok((start, part))
    }

    /// Whether the next step adds a point.
    fn needs_points(&self) -> bool {
        !matches!(self.progress, None | Some((_, Missing::Nothing)))
    }

    /// The start of `attempt` and its partition: a copy of the one `starts` keeps, else a
    /// new one, kept when it needs points.
    fn of(
        starts: &mut Starts,
        attempt: Attempt,
        schedule: Schedule,
        input: &Input,
    ) -> Result<(Self, Partition)> {
        if let Some(s) = starts.attempts.iter().find(|s| s.shrink == attempt.shrink) {
            return Ok((s.clone(), Partition::new(input.bounding)));
        }
        let (s, part) = Start::new(input, attempt.shrink, schedule, starts)?;
        if s.needs_points() {
            starts.attempts.push(s.clone());
        }
        Ok((s, part))
    }
}

/// One attempt at recovery with `schedule`: `intersections` runs before the first point is
/// added on the surface; `starts` are kept from one attempt to the next.
fn recover_by(
    input: &Input,
    intersections: &mut IntersectionCheck,
    starts: &mut Starts,
    attempt: Attempt,
    schedule: Schedule,
) -> Result<Recovered> {
    let Input {
        points,
        bounding,
        first_hull,
        ..
    } = *input;
    let (
        Start {
            mut mesh, progress, ..
        },
        mut part,
    ) = Start::of(starts, attempt, schedule, input)?;
    let budget = attempt.budget(bounding.len());
    if let Some((mut progress, missing)) = progress {
        let mut points = Points {
            budget,
            first: true,
            before_points: &mut |absent| intersections.run_on(Some(absent)),
        };
        progress.finish(
            &mut mesh,
            &mut part,
            missing,
            schedule,
            attempt,
            &mut points,
        )?;
    }
    let normals: Vec<Point> = bounding.iter().map(|f| unit_normal(points, *f)).collect();
    suppress::suppress_all(&mut mesh, &mut part, &normals, first_hull)?;
    // Points left on the surface (on the convex hull's triangles, where it is kept) are
    // output with their rounded coordinates.
    if !mesh.round_points_on_surface() {
        return Err(Error::new(
            ErrorKind::Limit,
            "a point left on the convex hull is too near a plane of its tetrahedra once rounded",
        ));
    }
    // The copies serve attempts after a failed recovery; past it, they are freed.
    starts.attempts.clear();
    let recovered = removed(
        input,
        classified(input, mesh, part)?,
        suppress::FIRST_REMOVAL,
    )?;
    // Where points are left in the kept regions, a second removal with stars grown by more
    // layers, after the relocation (a moved point may now go with fewer). It only removes
    // points: each schedule's count can only fall. Interior points with and without it:
    // anchor 12 -> 9, joint 4 -> 2, handle 8 -> 7, pipe 7 -> 6, sphere966 1 -> 0 (TetGen 24,
    // 3, 0, 18, 27), Chazelle's polyhedra with two to four notches a side unchanged, with
    // five 35 -> 27. Made in place of the first removal instead (8 layers, more passes), it
    // changed which schedule won, and Chazelle's polyhedron with four notches a side kept
    // 23 points, not 22.
    removed(input, recovered, suppress::SECOND_REMOVAL)
}

/// Removes what `removal` can of the points in the kept regions of `recovered`
/// ([`suppress::merge_interior`]), moves every point left to a better place
/// ([`suppress::relocate_interior`]) and finds the regions again. The points outside the
/// kept regions are dropped with them and are left alone: removing them too took anchor
/// 4.6 s instead of 3.2, joint 1.86 s instead of 1.32 (medians of 3), for the same counts.
fn removed(input: &Input, recovered: Recovered, removal: suppress::Removal) -> Result<Recovered> {
    if recovered.kept.is_empty() {
        return Ok(recovered);
    }
    let Recovered {
        mut mesh,
        part,
        kept,
        ..
    } = recovered;
    suppress::merge_interior(&mut mesh, &part.protected, &kept, removal)?;
    suppress::relocate_interior(&mut mesh, &part, input.first_added());
    classified(input, mesh, part)
}

/// The regions of the recovered `mesh` and the points added in them.
fn classified(input: &Input, mut mesh: TetMesh, part: Partition) -> Result<Recovered> {
    let Input {
        bounding,
        first_hull,
        options,
        ..
    } = *input;
    let first = input.first_added();
    // The hull's triangles are in pieces where points stayed on them.
    let facets: Vec<[u32; 3]> = if options.keep_convex_hull {
        let pieces = part
            .all_subfaces()
            .into_iter()
            .filter(|&(f, _)| f >= first_hull);
        let tris = bounding[..first_hull].iter().copied();
        tris.chain(pieces.map(|(_, t)| t)).collect()
    } else {
        bounding.to_vec()
    };
    let regions = classify::regions(&mut mesh, &facets, first_hull, options)?;
    // The added points are few: their stars are looked at, not the mesh.
    let kept = (first..mesh.points.len() as u32)
        .filter(|&v| mesh.in_mesh(v) && mesh.ball(v).iter().any(|&t| regions.kept(t)))
        .collect();
    Ok(Recovered {
        mesh,
        part,
        regions,
        kept,
    })
}

/// The tetrahedralization of `tris` from its recovered mesh and regions: optional quality
/// refinement and flips, output arrays.
fn complete(
    recovered: Recovered,
    points: &[Point],
    tris: &[[u32; 3]],
    options: &SurfaceOptions,
) -> Result<Mesh> {
    let Recovered {
        mut mesh,
        part,
        mut regions,
        ..
    } = recovered;
    let refined =
        options.max_radius_edge_ratio > 0.0 || regions.max_volume.iter().any(|&v| v > 0.0);
    let radii = if refined {
        Some(refine::refine(
            &mut mesh,
            &part.protected,
            &mut regions,
            options.max_radius_edge_ratio,
            points.len() as u32,
        )?)
    } else {
        None
    };
    // Flips that raise the worst shape in the kept regions (TetGen optimizes its meshes so):
    // after refinement for a ratio bound, of every tetrahedron shaped worse than half a
    // regular one; otherwise of the nearly flat ones alone, which an input triangle's flip
    // makes where the surface is nearly planar (a 2-3 flip recovering the diagonal of a
    // quadrilateral of nearly coplanar vertices leaves the flat tetrahedron of its four
    // corners).
    let ratio = options.max_radius_edge_ratio;
    // Without a ratio bound, the flips never raise the worst ratio of what they replace;
    // with one, only tetrahedra with three or four vertices on the surface may stay above
    // it. Where a volume bound applies, none may, and no new tetrahedron is larger than the
    // largest it replaces.
    let volumes = regions.max_volume.iter().any(|&v| v > 0.0);
    // The surface vertices, for the flips' exemption and the splits' candidates.
    let on_surface = if ratio > 0.0 {
        part.protected.vertices_on_edges(mesh.points.len())
    } else {
        Vec::new()
    };
    let exempt = match (ratio > 0.0, volumes) {
        (false, _) => flips::Exempt::All,
        (true, false) => flips::Exempt::OnSurface(&on_surface),
        (true, true) => flips::Exempt::None,
    };
    let bound = flips::Bound {
        below: if ratio > 0.0 {
            flips::IMPROVED_BELOW
        } else {
            flips::FLAT_BELOW
        },
        ratio,
        exempt,
        no_larger: volumes,
    };
    let protected = &part.protected;
    let kept = kept_tetrahedra(&mesh, &regions);
    flips::improve_by_flips(&mut mesh, protected, bound, kept, &mut told(&mut regions))?;
    // With a ratio bound, the flat tetrahedra left far above it on the surface are split, and
    // what the splits make above it refined: those with an input facet, and those with three
    // or four vertices on the surface, which the flips may leave above the bound.
    if let Some(radii) = radii.filter(|_| ratio > 0.0) {
        let at_surface = |&t: &u32| {
            regions.kept(t)
                && ((0..4).any(|i| regions.on_surface(t, i))
                    || flips::on_surface(&on_surface, &mesh.tets.vertices(t)))
        };
        let candidates: Vec<u32> = mesh.tets.live().filter(at_surface).collect();
        // What the splits and their refinement make is noted: it gets the flips too.
        mesh.begin();
        let new = wedges::split_wedges(
            &mut mesh,
            protected,
            bound,
            &candidates,
            &mut told(&mut regions),
        )?;
        if !new.is_empty() {
            refine::refine_these(&mut mesh, protected, &mut regions, (ratio, radii), new)?;
        }
        let change = mesh.end();
        let made: Vec<u32> = (change.created.iter())
            .filter_map(|&q| mesh.tet_of(q))
            .filter(|&t| regions.kept(t))
            .collect();
        flips::improve_by_flips(&mut mesh, protected, bound, made, &mut told(&mut regions))?;
    }
    // With a ratio bound, the points inside the regions of the tetrahedra with a small
    // dihedral angle move where their balls are better shaped, and the flips follow.
    if ratio > 0.0 {
        let kept = kept_tetrahedra(&mesh, &regions);
        let moved = smooth::smooth_points(&mut mesh, &on_surface, bound, &kept);
        flips::improve_by_flips(&mut mesh, protected, bound, moved, &mut told(&mut regions))?;
    }
    classify::assemble(&mesh, points.len(), tris, &regions, &|v| {
        part.host.contains_key(&v)
    })
}

/// The tetrahedra of the kept regions.
fn kept_tetrahedra(mesh: &TetMesh, regions: &classify::Regions) -> Vec<u32> {
    mesh.tets.live().filter(|&t| regions.kept(t)).collect()
}

/// How the mesh's optimization tells its changes: the new tetrahedra go in the region of the
/// old one named.
fn told(regions: &mut classify::Regions) -> impl FnMut(&TetMesh, u32, &[u32]) + '_ {
    |mesh, old, new| {
        let c = regions.component[old as usize];
        regions.assign(mesh, new, c);
    }
}

/// Flips the missing sub-edge `e`, where it lies inside an input triangle, to the other
/// diagonal of its two subfaces when that is an edge of the mesh: no point is needed on it.
/// Where the surface is planar over several triangles, splitting such sub-edges at their
/// crossings crowds points a rounding apart; with the flip, anchor meshes in 2.0 s instead
/// of 4.0 s with the same 10 interior points (the first schedule's later attempts succeed
/// sooner), and Chazelle's polyhedra keep 5, 11, 15, 21, 32 and 38 points with two to seven
/// notches a side (5, 13, 15, 18, 34 and 38 without; seven 28 s against 20 s in CI runs).
fn flipped_to_edge(mesh: &mut TetMesh, part: &mut Partition, e: [u32; 2]) -> bool {
    let partition::Host::Face(f) = part.host_of_subedge(e[0], e[1]) else {
        return false;
    };
    let Some(quad) = part.flippable_in(f, e, &mesh.points) else {
        return false;
    };
    let [x, w] = quad.other_diagonal();
    if mesh.find_edge(x, w).is_none() {
        return false;
    }
    part.flip(f, &quad);
    true
}

/// What flips leave missing ([`Progress::by_flips`]).
#[derive(Clone)]
enum Missing {
    /// Nothing: every subface is a facet.
    Nothing,
    /// These sub-edges.
    Edges(Vec<[u32; 2]>),
    /// These subfaces (numbers of their input triangles, and vertices), every sub-edge
    /// being an edge.
    Faces(Vec<(usize, [u32; 3])>),
}

/// What recovery has made present: the protected sub-edges and subfaces that are
/// edges and facets of the mesh stay so (flips never destroy them).
#[derive(Clone)]
struct Progress {
    edges_done: HashSet<[u32; 2]>,
    faces_done: HashSet<[u32; 3]>,
    /// The mesh's [`EdgeOrder`].
    order: EdgeOrder,
}

impl Progress {
    /// `None` when every subface is already a facet of the mesh.
    fn start(mesh: &mut TetMesh, part: &Partition) -> Option<Self> {
        let (edges_done, present) = mesh.present(&part.protected)?;
        let mut faces_done: HashSet<[u32; 3]> =
            HashSet::with_capacity_and_hasher(present.len(), Default::default());
        faces_done.extend(
            part.all_subfaces()
                .into_iter()
                .map(|(_, f)| f)
                .filter(|f| present.contains(&tetmesh::key(*f))),
        );
        Some(Progress {
            edges_done,
            faces_done,
            order: mesh.edge_order,
        })
    }

    /// Recovers the missing sub-edges by flips ([`edges::recover_edge`]) in the passes of
    /// `schedule`, shrinking crossed shells with `shrink`; when none is left, the missing
    /// subfaces ([`faces::recover_face`]). Returns what is still missing.
    fn by_flips(
        &mut self,
        mesh: &mut TetMesh,
        part: &Partition,
        schedule: Schedule,
        shrink: bool,
    ) -> Result<Missing> {
        let stuck = self.missing_edges(part);
        let stuck = self.edge_passes(mesh, part, stuck, schedule, shrink)?;
        self.faces_after(mesh, part, stuck)
    }

    /// The sub-edges of the partition that are not edges yet, in the mesh's [`EdgeOrder`].
    fn missing_edges(&self, part: &Partition) -> Vec<[u32; 2]> {
        let mut missing: Vec<[u32; 2]> = part
            .subedges()
            .into_iter()
            .filter(|e| !self.edges_done.contains(e))
            .collect();
        if self.order == EdgeOrder::Reversed {
            missing.reverse();
        }
        missing
    }

    /// The passes of `schedule` over the missing sub-edges `stuck`; those still missing.
    fn edge_passes(
        &mut self,
        mesh: &mut TetMesh,
        part: &Partition,
        mut stuck: Vec<[u32; 2]>,
        schedule: Schedule,
        shrink: bool,
    ) -> Result<Vec<[u32; 2]>> {
        for &(depth, guard) in schedule {
            if stuck.is_empty() {
                break;
            }
            stuck = until_stable(stuck, |&e| {
                let done = edges::recover_edge(mesh, &part.protected, e, depth, guard, shrink)?;
                if done {
                    self.edges_done.insert(e);
                }
                Ok(done)
            })?;
        }
        Ok(stuck)
    }

    /// What is missing when the sub-edges `stuck` are: those, or when every sub-edge is an
    /// edge, the subfaces flips leave missing ([`faces::recover_face`]).
    fn faces_after(
        &mut self,
        mesh: &mut TetMesh,
        part: &Partition,
        stuck: Vec<[u32; 2]>,
    ) -> Result<Missing> {
        if !stuck.is_empty() {
            return Ok(Missing::Edges(stuck));
        }
        let pending: Vec<(usize, [u32; 3])> = part
            .all_subfaces()
            .into_iter()
            .filter(|(_, f)| !self.faces_done.contains(f))
            .collect();
        let stuck = until_stable(pending, |&(_, f)| {
            let done = faces::recover_face(mesh, &part.protected, f)?;
            if done {
                self.faces_done.insert(f);
            }
            Ok(done)
        })?;
        Ok(if stuck.is_empty() {
            Missing::Nothing
        } else {
            Missing::Faces(stuck)
        })
    }

    /// Recovers every subface (§5.2) from what [`Progress::by_flips`] left `missing`: where
    /// flips fail, a point is added on the surface at the first crossing and flips start
    /// again with the new, smaller pieces (points inside the volume first with
    /// `attempt.interior`, [`Progress::inside_first`]; subfaces made Delaunay around each
    /// point with `attempt.delaunay`). `points` counts them.
    fn finish(
        &mut self,
        mesh: &mut TetMesh,
        part: &mut Partition,
        mut missing: Missing,
        schedule: Schedule,
        attempt: Attempt,
        points: &mut Points,
    ) -> Result<()> {
        loop {
            match missing {
                Missing::Nothing => return Ok(()),
                Missing::Edges(stuck) => {
                    let Some(stuck) = self.inside_first(mesh, part, stuck, attempt, points)? else {
                        missing = self.by_flips(mesh, part, schedule, attempt.shrink)?;
                        continue;
                    };
                    for [a, b] in stuck {
                        // A split's flips may have taken a later one away.
                        if !part.protected.edge(a, b) || flipped_to_edge(mesh, part, [a, b]) {
                            continue;
                        }
                        points.one(mesh, part, &self.faces_done, || {
                            format!("sub-edge ({a}, {b})")
                        })?;
                        if let Some(c) = edges::first_crossing(mesh, a, b)? {
                            let s = steiner::split_subedge(mesh, part, a, b, c)?;
                            if let Some(s) = s.filter(|_| attempt.delaunay) {
                                part.delaunay_around(s, &mesh.points);
                            }
                        }
                    }
                }
                Missing::Faces(stuck) => {
                    for (f, t) in stuck {
                        if !part.protected.facet(t) {
                            continue;
                        }
                        points.one(mesh, part, &self.faces_done, || format!("triangle {f}"))?;
                        if let Some(&(e, _)) = faces::crossing_edges(mesh, t).first() {
                            let s = steiner::split_subface(mesh, part, f, t, e)?;
                            if attempt.delaunay {
                                part.delaunay_around(s, &mesh.points);
                            }
                        }
                    }
                }
            }
            missing = self.by_flips(mesh, part, schedule, attempt.shrink)?;
        }
    }

    /// With `attempt.interior`, a point inside the volume for each sub-edge of `stuck` where
    /// one recovers it, before any on it: `None` when that recovered some, else the sub-edges
    /// still missing.
    fn inside_first(
        &mut self,
        mesh: &mut TetMesh,
        part: &Partition,
        stuck: Vec<[u32; 2]>,
        attempt: Attempt,
        points: &mut Points,
    ) -> Result<Option<Vec<[u32; 2]>>> {
        if !attempt.interior {
            return Ok(Some(stuck));
        }
        let before = stuck.len();
        let stuck = until_stable(stuck, |&e| {
            let may_add = points.budget > 0;
            let Some(added) = interior::recover_edge(mesh, &part.protected, e, may_add)? else {
                return Ok(false);
            };
            if added {
                spend(&mut points.budget, || {
                    format!("sub-edge ({}, {})", e[0], e[1])
                })?;
            }
            self.edges_done.insert(e);
            Ok(true)
        })?;
        Ok((stuck.len() == before).then_some(stuck))
    }
}

/// The points [`Progress::finish`] may still add (`budget`), and whether it has added one yet:
/// before the first on the surface, `before_points` is told the triangles (numbers in the
/// partition) that may not be facets of the mesh, and may stop the recovery.
struct Points<'a> {
    budget: usize,
    first: bool,
    before_points: &'a mut dyn FnMut(&[usize]) -> Result<()>,
}

impl Points<'_> {
    /// Counts a point about to be added on the surface to recover `what`.
    fn one(
        &mut self,
        mesh: &mut TetMesh,
        part: &Partition,
        present: &HashSet<[u32; 3]>,
        what: impl Fn() -> String,
    ) -> Result<()> {
        if std::mem::take(&mut self.first) {
            let mut absent: Vec<usize> = part
                .all_subfaces()
                .into_iter()
                .filter(|(_, f)| !present.contains(f) && mesh.find_face(*f).is_none())
                .map(|(k, _)| k)
                .collect();
            absent.dedup();
            (self.before_points)(&absent)?;
        }
        spend(&mut self.budget, what)
    }
}

/// The tetrahedra filling the closed surface `triangles` (indices into `points`: the
/// boundary of a region of tetrahedra) with no added point, the vertices `inner` (inside it)
/// among theirs, as this module's recovery finds them; `None` when it needs a point.
fn fill_without_points(
    points: &[Point],
    triangles: &[[u32; 3]],
    inner: &[u32],
    order: EdgeOrder,
) -> Option<Vec<[u32; 4]>> {
    let mut mesh = enclosed_delaunay(points, triangles, inner).ok()?;
    mesh.edge_order = order;
    let part = Partition::new(triangles);
    if let Some(mut progress) = Progress::start(&mut mesh, &part) {
        let missing = progress.by_flips(&mut mesh, &part, FILL, false).ok()?;
        if !matches!(missing, Missing::Nothing) {
            return None;
        }
    }
    let n = points.len() as u32;
    let start = mesh.search_ball(n, |_, t| Some(t))?;
    let mut outside = vec![false; mesh.tets.slots()];
    outside[start as usize] = true;
    let mut stack = vec![start];
    while let Some(t) = stack.pop() {
        for i in 0..4 {
            let u = mesh.tets.neighbor(t, i);
            if !outside[u as usize] && !part.protected.facet(mesh.facet(t, i)) {
                outside[u as usize] = true;
                stack.push(u);
            }
        }
    }
    let inside: Vec<[u32; 4]> = mesh
        .tets
        .live()
        .filter(|&t| !outside[t as usize])
        .map(|t| mesh.tets.vertices(t))
        .collect();
    let used = |v: &u32| inside.iter().any(|q| q.contains(v));
    (inside.iter().flatten().all(|&v| v < n) && inner.iter().all(used)).then_some(inside)
}

/// Counts one added point against `budget`.
fn spend(budget: &mut usize, what: impl Fn() -> String) -> Result<()> {
    if *budget == 0 {
        return Err(Error::new(
            ErrorKind::Limit,
            format!("too many points added on the surface to recover {}", what()),
        ));
    }
    *budget -= 1;
    Ok(())
}

/// The unit normal of triangle `f` (right-hand rule).
fn unit_normal(points: &[Point], f: [u32; 3]) -> Point {
    let [a, b, c] = f.map(|v| points[v as usize]);
    let n = crate::geometry::cross(&crate::geometry::sub(&b, &a), &crate::geometry::sub(&c, &a));
    let l = crate::geometry::norm(&n);
    [n[0] / l, n[1] / l, n[2] / l]
}

/// Applies `recover` to every item, then again to those it failed on, as long as a pass
/// recovers something (recovering one item can unblock another); returns the items still
/// failing.
fn until_stable<T>(
    mut pending: Vec<T>,
    mut recover: impl FnMut(&T) -> Result<bool>,
) -> Result<Vec<T>> {
    loop {
        let before = pending.len();
        let mut still = Vec::new();
        for item in pending {
            if !recover(&item)? {
                still.push(item);
            }
        }
        if still.is_empty() || still.len() == before {
            return Ok(still);
        }
        pending = still;
    }
}

/// Checks the options: bounds finite and meaningful, and nothing this version cannot honour.
fn check_options(options: &SurfaceOptions) -> Result<()> {
    let ratio = options.max_radius_edge_ratio;
    if !(ratio == 0.0 || ratio >= 1.2 && ratio.is_finite()) {
        return Err(Error::invalid_argument(format!(
            "max_radius_edge_ratio {ratio} must be 0 (no quality refinement) or finite and \
             >= 1.2 (a regular tetrahedron has 0.61; refinement below about 1.1 does not end)"
        )));
    }
    let volumes = std::iter::once(("max_volume".to_string(), options.max_volume)).chain(
        options
            .regions
            .iter()
            .enumerate()
            .map(|(k, r)| (format!("the max_volume of region seed {k}"), r.max_volume)),
    );
    for (what, v) in volumes {
        if !(v >= 0.0 && v.is_finite()) {
            return Err(Error::invalid_argument(format!(
                "{what} is {v}: it must be 0 (no bound) or a positive finite volume"
            )));
        }
    }
    Ok(())
}

/// The Delaunay triangulation of the vertices the triangles use, of the `isolated` vertices,
/// and of the corners of a box three times as large as theirs (George and Borouchaki §5.1).
fn enclosed_delaunay(
    points: &[Point],
    triangles: &[[u32; 3]],
    isolated: &[u32],
) -> Result<TetMesh> {
    let used: Vec<u32> = {
        let mut meshed = vec![false; points.len()];
        for &v in triangles.iter().flatten().chain(isolated) {
            meshed[v as usize] = true;
        }
        (0..points.len() as u32)
            .filter(|&v| meshed[v as usize])
            .collect()
    };
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &v in &used {
        for k in 0..3 {
            lo[k] = lo[k].min(points[v as usize][k]);
            hi[k] = hi[k].max(points[v as usize][k]);
        }
    }
    let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let mut all = points.to_vec();
    let mut with_box = used.clone();
    for corner in 0..8 {
        let c = [0, 1, 2].map(|k| {
            if corner >> k & 1 == 0 {
                lo[k] - size
            } else {
                hi[k] + size
            }
        });
        with_box.push(all.len() as u32);
        all.push(c);
    }
    TetMesh::delaunay(all, &with_box)
}
