//! Benchmark (not a test): 2D Delaunay triangulation of random points by delmesh and by the
//! Rust crate `spade` (`DelaunayTriangulation::bulk_load`), the triangulation Rust users pick.
//! The C benchmark `c_tests/bench_2d` compares with CGAL; a Rust crate cannot be linked there,
//! hence this example (spade is a dev-dependency only).
//!
//! ```text
//! cargo run --release --example bench_spade_2d [N]        (N = 1000000 by default)
//! ```
//!
//! The points are those of `bench_2d` (the same splitmix64 stream and seed): uniform in the
//! unit square. Each run is a separate process (this program again with `--child TOOL N`), so
//! that its peak resident memory is its own; 3 repetitions alternating the tools, medians. The
//! time covers the triangulation and the export of its triangles as input-index triples, not
//! input generation or destruction.

use std::process::Command;
use std::time::Instant;

use spade::{DelaunayTriangulation, HasPosition, Point2, Triangulation};

const REPETITIONS: usize = 3;
const TOOLS: [&str; 2] = ["delmesh", "spade"];

/// splitmix64, as `c_tests/common/prng.h`.
struct Prng(u64);

impl Prng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn uniform(&mut self) -> f64 {
        (self.next() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

fn points(n: usize) -> Vec<f64> {
    let mut g = Prng(0x2D00_BE7C + n as u64);
    (0..2 * n).map(|_| g.uniform()).collect()
}

/// A spade vertex that remembers its input index.
struct Indexed {
    position: Point2<f64>,
    index: u32,
}

impl HasPosition for Indexed {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.position
    }
}

/// The peak resident memory of this process, in MB (Linux; 0 elsewhere).
fn peak_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(0.0, |kb| kb / 1024.0)
}

/// One run: prints "<seconds> <triangles> <peak MB>".
fn child(tool: &str, n: usize) {
    let xy = points(n);
    let start = Instant::now();
    let triangles: Vec<u32> = match tool {
        "delmesh" => {
            delmesh::mesh2d::delaunay_2d(&xy)
                .expect("delmesh")
                .triangles
        }
        "spade" => {
            let vertices: Vec<Indexed> = xy
                .chunks_exact(2)
                .enumerate()
                .map(|(i, p)| Indexed {
                    position: Point2::new(p[0], p[1]),
                    index: i as u32,
                })
                .collect();
            let dt = DelaunayTriangulation::<Indexed>::bulk_load(vertices).expect("spade");
            let triangles = dt
                .inner_faces()
                .flat_map(|f| f.vertices().map(|v| v.data().index))
                .collect();
            std::mem::forget(dt); // destruction not timed, as for delmesh and CGAL
            triangles
        }
        other => panic!("unknown tool {other}"),
    };
    let seconds = start.elapsed().as_secs_f64();
    println!("{seconds:.6} {} {:.1}", triangles.len() / 3, peak_mb());
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() == 4 && args[1] == "--child" {
        child(&args[2], args[3].parse().expect("N"));
        return;
    }
    let n: usize = args.get(1).map_or(1_000_000, |a| a.parse().expect("N"));
    let exe = std::env::current_exe().expect("own path");
    println!("delmesh vs spade 2D Delaunay, {n} random points in the unit square");
    println!("each run in its own process; {REPETITIONS} repetitions, alternating; medians\n");
    let mut seconds = [Vec::new(), Vec::new()];
    let mut memory = [Vec::new(), Vec::new()];
    let mut counts = [0usize; 2];
    for rep in 0..REPETITIONS {
        for k in 0..TOOLS.len() {
            let tool = (k + rep) % TOOLS.len();
            let out = Command::new(&exe)
                .args(["--child", TOOLS[tool], &n.to_string()])
                .output()
                .expect("spawn");
            let text = String::from_utf8_lossy(&out.stdout);
            let fields: Vec<f64> = text
                .split_whitespace()
                .filter_map(|f| f.parse().ok())
                .collect();
            if !out.status.success() || fields.len() != 3 {
                eprintln!(
                    "{} failed: {}",
                    TOOLS[tool],
                    String::from_utf8_lossy(&out.stderr)
                );
                std::process::exit(1);
            }
            println!(
                "  run rep {} {:<7}: {:8.3} s {:8.1} MB {:10} triangles",
                rep + 1,
                TOOLS[tool],
                fields[0],
                fields[2],
                fields[1]
            );
            seconds[tool].push(fields[0]);
            memory[tool].push(fields[2]);
            counts[tool] = fields[1] as usize;
        }
    }
    let t = seconds.map(median);
    let m = memory.map(median);
    println!(
        "\nmedians: delmesh {:.3} s {:.1} MB, spade {:.3} s {:.1} MB; \
         spade/delmesh: time {:.2}, memory {:.2}; triangles {} / {}",
        t[0],
        m[0],
        t[1],
        m[1],
        t[1] / t[0],
        m[1] / m[0],
        counts[0],
        counts[1]
    );
}
