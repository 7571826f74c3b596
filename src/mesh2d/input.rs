//! Checks of a planar straight-line graph (points and segments) before triangulation: what
//! Pébay §3 assumes of a constraint field (Definition 1.5: edges between distinct points of
//! `S`, meeting only at their ends). Every failure names its culprits (at most
//! [`MAX_CULPRITS`] of them, then a count).
//!
//! On request ([`Crossings::Split`]), segments that cross properly are split at their
//! intersection points instead ([`crossing`](super::crossing)); the pieces are then checked
//! as input segments are, a failure there being a rounding limit (`ErrorKind::Limit`).
//! T-junctions (a segment end on another segment) and collinear overlaps stay errors.

use super::cloud::Cloud;
use super::crossing::split_at_crossings;
use crate::error::{Error, ErrorKind, Result};
use crate::predicates::{orient2d, Sign};
use crate::triangulation::MAX_COORDINATE;

/// Culprits named in one message.
pub const MAX_CULPRITS: usize = 5;

/// Largest number of points: indices are `u32` and the infinite vertex is `u32::MAX`.
pub const MAX_POINTS_2D: usize = (u32::MAX / 2) as usize;

/// The points of `xy` (x y interleaved), checked finite and within the coordinate limit.
pub fn points(xy: &[f64]) -> Result<Vec<[f64; 2]>> {
    point_slice(xy).map(<[[f64; 2]]>::to_vec)
}

/// [`points`] without the copy: `xy` seen as points.
pub fn point_slice(xy: &[f64]) -> Result<&[[f64; 2]]> {
    let (points, rest) = xy.as_chunks::<2>();
    if !rest.is_empty() {
        return Err(Error::invalid_input(format!(
            "{} coordinates is not a multiple of 2",
            xy.len()
        )));
    }
    if points.len() > MAX_POINTS_2D {
        return Err(Error::invalid_input(format!(
            "{} points is more than the limit {MAX_POINTS_2D}",
            points.len()
        )));
    }
    let bad: Vec<usize> = (0..points.len())
        .filter(|&i| {
            points[i]
                .iter()
                .any(|x| !x.is_finite() || x.abs() > MAX_COORDINATE)
        })
        .collect();
    if !bad.is_empty() {
        return Err(Error::invalid_input(format!(
            "point{} {} ha{} a non-finite coordinate or one of magnitude above {MAX_COORDINATE:e}",
            plural(bad.len()),
            culprits(&bad),
            if bad.len() == 1 { "s" } else { "ve" }
        )));
    }
    Ok(points)
}

/// What to do with segments that cross properly.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Crossings {
    /// Fail, naming the crossing pairs.
    #[default]
    Reject,
    /// Split them at their intersection points (see the module documentation).
    Split,
}

/// The checked constraint field of [`segments`].
#[derive(Clone, Debug, Default)]
pub struct Segments {
    /// The segments (after splitting: their pieces), by input segment and along it, each
    /// oriented as its input segment.
    pub segs: Vec<[u32; 2]>,
    /// The input segment each comes from.
    pub origin: Vec<u32>,
    /// Intersection points added to the cloud (after the points it held), when splitting.
    pub intersections: usize,
}

/// The segments of `pairs` (2 point indices each) with their ends mapped through `first`
/// (duplicate points merged), repeated segments dropped (the first kept), in input order,
/// with the index of the input segment each comes from. Fails on an index out of range, a
/// zero-length segment, a point on an open segment, or two crossing segments; with
/// [`Crossings::Split`], crossing segments are split instead, the intersection points pushed
/// to `cloud` (which holds `points`, with those that are not their own `first` unindexed).
pub fn segments(
    pairs: &[u32],
    points: &[[f64; 2]],
    first: &[u32],
    cloud: &mut Cloud,
    crossings: Crossings,
) -> Result<Segments> {
    let (pairs, rest) = pairs.as_chunks::<2>();
    if !rest.is_empty() {
        return Err(Error::invalid_input("segment indices are not in pairs"));
    }
    let n = points.len();
    let out_of_range: Vec<usize> = (0..pairs.len())
        .filter(|&k| pairs[k].iter().any(|&i| i as usize >= n))
        .collect();
    if !out_of_range.is_empty() {
        return Err(Error::invalid_input(format!(
            "segment{} {} reference{} a point index out of range (n_points = {n})",
            plural(out_of_range.len()),
            culprits(&out_of_range),
            if out_of_range.len() == 1 { "s" } else { "" }
        )));
    }
    let merged: Vec<[u32; 2]> = pairs.iter().map(|s| s.map(|i| first[i as usize])).collect();
    let zero: Vec<usize> = (0..merged.len())
        .filter(|&k| merged[k][0] == merged[k][1])
        .collect();
    if !zero.is_empty() {
        return Err(Error::invalid_input(format!(
            "segment{} {} ha{} zero length (both ends at the same point)",
            plural(zero.len()),
            culprits(&zero),
            if zero.len() == 1 { "s" } else { "ve" }
        )));
    }
    let keep = first_of_each(&merged, n);
    let mut kept = Vec::new();
    let mut origin = Vec::new();
    for (k, s) in merged.iter().enumerate() {
        if keep[k] {
            kept.push(*s);
            origin.push(k as u32);
        }
    }
    fail_with(points_on_segments(&kept, &origin, &cloud.points, cloud))?;
    let crossing = crossing_pairs(&kept, &cloud.points, cloud);
    if crossing.is_empty() {
        return Ok(Segments {
            segs: kept,
            origin,
            intersections: 0,
        });
    }
    if crossings == Crossings::Reject {
        return fail_with(crossing_messages(&crossing, &origin)).map(|()| Segments::default());
    }
    let (pieces, of_segment, intersections) = split_at_crossings(&kept, &crossing, cloud);
    let piece_origin: Vec<u32> = of_segment.iter().map(|&s| origin[s as usize]).collect();
    let mut found = coincident_points(cloud, n);
    found.extend(points_on_segments(
        &pieces,
        &piece_origin,
        &cloud.points,
        cloud,
    ));
    found.extend(crossing_messages(
        &crossing_pairs(&pieces, &cloud.points, cloud),
        &piece_origin,
    ));
    fail_with(found).map_err(|e| {
        Error::new(
            ErrorKind::Limit,
            format!(
                "splitting the crossing segments at their intersection points, rounded to \
                 doubles, gives an invalid constraint field: {}",
                e.message
            ),
        )
    })?;
    Ok(Segments {
        segs: pieces,
        origin: piece_origin,
        intersections,
    })
}

/// For each segment of `segs` (ends below `n`, in either order), whether it is the first with
/// its pair of ends: the segments grouped by smaller end (a counting sort), each group sorted
/// by larger end then index.
fn first_of_each(segs: &[[u32; 2]], n: usize) -> Vec<bool> {
    let mut start = vec![0usize; n + 1];
    for s in segs {
        start[s[0].min(s[1]) as usize + 1] += 1;
    }
    for i in 1..start.len() {
        start[i] += start[i - 1];
    }
    let mut by_end = vec![(0u32, 0u32); segs.len()];
    let mut next = start.clone();
    for (k, s) in segs.iter().enumerate() {
        let low = s[0].min(s[1]) as usize;
        by_end[next[low]] = (s[0].max(s[1]), k as u32);
        next[low] += 1;
    }
    let mut first = vec![false; segs.len()];
    for i in 0..n {
        let group = &mut by_end[start[i]..start[i + 1]];
        group.sort_unstable();
        for same in group.chunk_by(|x, y| x.0 == y.0) {
            first[same[0].1 as usize] = true;
        }
    }
    first
}

/// A message for every point from `from` on (the rounded intersection points) that has the
/// coordinates of another point of `cloud`.
fn coincident_points(cloud: &Cloud, from: usize) -> Vec<String> {
    let mut found = Vec::new();
    for i in from..cloud.points.len() {
        let p = cloud.points[i];
        cloud.candidates(p, p, |j| {
            if j as usize != i && cloud.points[j as usize] == p {
                found.push(format!("intersection point {i} rounds onto point {j}"));
            }
        });
    }
    found
}

/// A message for every point on the open segment of a segment: collinear with its ends, in
/// their bounding box, and at neither (the candidates are those of the grid buckets of the
/// box).
fn points_on_segments(
    segs: &[[u32; 2]],
    origin: &[u32],
    points: &[[f64; 2]],
    cloud: &Cloud,
) -> Vec<String> {
    let mut found = Vec::new();
    for (k, s) in segs.iter().enumerate() {
        let (a, b) = (&points[s[0] as usize], &points[s[1] as usize]);
        let lo = [a[0].min(b[0]), a[1].min(b[1])];
        let hi = [a[0].max(b[0]), a[1].max(b[1])];
        cloud.candidates(lo, hi, |q| {
            let p = &points[q as usize];
            if p != a
                && p != b
                && (0..2).all(|j| lo[j] <= p[j] && p[j] <= hi[j])
                && orient2d(a, b, p) == Sign::Zero
            {
                found.push(format!("point {q} lies on segment {}", origin[k]));
            }
        });
    }
    found
}

/// The pairs of segments (indices into `segs`, sorted) that cross properly (the pairs that
/// touch share an end or were reported as a point on a segment). Candidate pairs have
/// overlapping bounding boxes and are listed in the grid buckets those boxes meet; each pair is
/// tested once, in the first bucket (lowest row, then column) the two boxes share.
fn crossing_pairs(segs: &[[u32; 2]], points: &[[f64; 2]], cloud: &Cloud) -> Vec<(u32, u32)> {
    let p = |i: u32| &points[i as usize];
    let boxes: Vec<[[f64; 2]; 2]> = segs
        .iter()
        .map(|s| {
            let (a, b) = (p(s[0]), p(s[1]));
            [
                [a[0].min(b[0]), a[1].min(b[1])],
                [a[0].max(b[0]), a[1].max(b[1])],
            ]
        })
        .collect();
    let cells: Vec<[usize; 4]> = boxes
        .iter()
        .map(|b| cloud.cells_of_box(b[0], b[1]))
        .collect();
    let columns = cloud.columns();
    let each_cell = |c: &[usize; 4], f: &mut dyn FnMut(usize)| {
        for y in c[1]..=c[3] {
            for x in c[0]..=c[2] {
                f(y * columns + x);
            }
        }
    };
    // The segments of each bucket, in increasing order, in one array.
    let mut start = vec![0usize; cloud.cell_count() + 1];
    for c in &cells {
        each_cell(c, &mut |id| start[id + 1] += 1);
    }
    for id in 1..start.len() {
        start[id] += start[id - 1];
    }
    let mut listed = vec![0u32; start[start.len() - 1]];
    let mut next = start.clone();
    for (k, c) in cells.iter().enumerate() {
        each_cell(c, &mut |id| {
            listed[next[id]] = k as u32;
            next[id] += 1;
        });
    }
    let mut found = Vec::new();
    for id in 0..start.len() - 1 {
        let list = &listed[start[id]..start[id + 1]];
        let (x, y) = (id % columns, id / columns);
        for (i, &s) in list.iter().enumerate() {
            for &t in &list[i + 1..] {
                let (cs, ct) = (&cells[s as usize], &cells[t as usize]);
                let (bs, bt) = (&boxes[s as usize], &boxes[t as usize]);
                if x != cs[0].max(ct[0])
                    || y != cs[1].max(ct[1])
                    || (0..2).any(|k| bs[1][k] < bt[0][k] || bt[1][k] < bs[0][k])
                {
                    continue;
                }
                let ([a, b], [c, d]) = (segs[s as usize], segs[t as usize]);
                if a == c || a == d || b == c || b == d {
                    continue;
                }
                let o1 = orient2d(p(a), p(b), p(c)) * orient2d(p(a), p(b), p(d));
                let o2 = orient2d(p(c), p(d), p(a)) * orient2d(p(c), p(d), p(b));
                if o1 == Sign::Negative && o2 == Sign::Negative {
                    found.push((s, t));
                }
            }
        }
    }
    found.sort_unstable();
    found
}

/// "segments i and j cross" for each pair, named by input segment.
fn crossing_messages(pairs: &[(u32, u32)], origin: &[u32]) -> Vec<String> {
    pairs
        .iter()
        .map(|&(s, t)| {
            let (i, j) = (origin[s as usize], origin[t as usize]);
            format!("segments {} and {} cross", i.min(j), i.max(j))
        })
        .collect()
}

fn fail_with(mut found: Vec<String>) -> Result<()> {
    if found.is_empty() {
        return Ok(());
    }
    found.sort();
    let more = found.len().saturating_sub(MAX_CULPRITS);
    found.truncate(MAX_CULPRITS);
    let mut message = found.join("; ");
    if more > 0 {
        message.push_str(&format!("; and {more} more"));
    }
    Err(Error::invalid_input(message))
}

fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

/// The first culprits' indices, comma-separated, and how many more.
fn culprits(list: &[usize]) -> String {
    let shown: Vec<String> = list
        .iter()
        .take(MAX_CULPRITS)
        .map(|i| i.to_string())
        .collect();
    let mut text = shown.join(", ");
    if list.len() > MAX_CULPRITS {
        text.push_str(&format!(" and {} more", list.len() - MAX_CULPRITS));
    }
    text
}
