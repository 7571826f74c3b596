//! Feeds point sets to the Delaunay and regular triangulations and checks them exactly.
//!
//! The bytes are read as small integer coordinates (so grids, coplanar and cospherical subsets
//! and duplicates are frequent) scaled by a power of two, optionally with weights; every
//! outcome must be a valid triangulation or a clean `InvalidInput` error.

#![no_main]

use delmesh::triangulation::Triangulation;
use delmesh::ErrorKind;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&head, body)) = data.split_first() else {
        return;
    };
    let weighted = head & 1 == 1;
    let scale = f64::powi(2.0, i32::from(head >> 1) - 64);
    let stride = if weighted { 4 } else { 3 };
    let records = body.chunks_exact(stride).take(400);
    let xyz: Vec<f64> = records
        .clone()
        .flat_map(|r| r[..3].iter().map(|&c| f64::from(c & 15) * scale))
        .collect();
    let weights: Vec<f64> = records.map(|r| f64::from(r[stride - 1] & 7) * scale * scale).collect();
    let mut t = match Triangulation::new(&xyz, weighted.then_some(&weights[..])) {
        Ok(t) => t,
        Err(e) => return assert_eq!(e.kind, ErrorKind::InvalidInput),
    };
    match t.insert_all() {
        Ok(()) => t.validate().unwrap(),
        Err(e) => assert_eq!(e.kind, ErrorKind::InvalidInput, "{e}"),
    }
});
