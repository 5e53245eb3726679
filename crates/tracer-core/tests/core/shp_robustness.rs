//! Mangled input never panics, hangs or allocates without bound: thousands of deterministic
//! byte mutations and truncations of a valid file, each read as `.shp` and as `.brs`.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;

use tracer_core::shp;

const SEED_FILE: &str = "\
;; Created by Lumicept\r
ProcessMesh\r
  TriangleSize     100.000000%\r
enddef\r
define breps brs_0\r
GeoChecked\r
vertices 4 ;; Number of vertices\r
   114.555   0.00000  -116.556\r
   1.000000e+000   -0.00000  -66.3538\r
   287.646   5.5  -113.536\r
   0   0   0\r
triangles 3 ;; Number of triangles\r
 0 1 2\r
 1 2 3\r
 3 2 0\r
parts 2 ;; Number of parts\r
 0  1  1\r
enddef\r
Light lamp\r
  position 1 2 3\r
enddef\r
set breps brs_0\r
  rotation 0.000000 0.000000 0.000000\r
  translation   0.00000   0.00000   0.00000\r
  scale   1.00000   1.00000   1.00000\r
enddef\r
";

/// xorshift64: deterministic, no dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Bytes that make interesting damage in this format.
const SPICE: &[u8] = b"0123456789 \t\r\n;;-+.eE\0\xFF\xC3xenddef";
const BIG_NUMBERS: [&str; 5] = ["999999999", "4294967295", "4294967296", "1e400", "nan"];

fn mutate(rng: &mut Rng, bytes: &mut Vec<u8>) {
    let at = rng.below(bytes.len() + 1);
    match rng.below(7) {
        0 if at < bytes.len() => bytes[at] = rng.next() as u8,
        1 if at < bytes.len() => bytes[at] = SPICE[rng.below(SPICE.len())],
        2 => bytes.insert(at, SPICE[rng.below(SPICE.len())]),
        3 => {
            let end = (at + rng.below(40)).min(bytes.len());
            bytes.drain(at..end);
        }
        4 => bytes.truncate(at),
        5 => {
            let number = BIG_NUMBERS[rng.below(BIG_NUMBERS.len())].as_bytes();
            bytes.splice(at..at, number.iter().copied());
        }
        _ => {
            // Duplicate a stretch, as a botched copy and paste would.
            let end = (at + rng.below(120)).min(bytes.len());
            let stretch = bytes[at..end].to_vec();
            bytes.splice(at..at, stretch);
        }
    }
}

#[test]
fn the_seed_file_is_valid() {
    let desc = shp::parse_shp(SEED_FILE.as_bytes(), Path::new("seed.shp")).unwrap();
    assert_eq!(desc.breps[0].parts, [0, 1, 1]);
}

#[test]
fn mutations_never_panic() {
    let path = Path::new("fuzz.shp");
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let (mut ok, mut err) = (0, 0);
    for _ in 0..20_000 {
        let mut bytes = SEED_FILE.as_bytes().to_vec();
        for _ in 0..1 + rng.below(4) {
            mutate(&mut rng, &mut bytes);
        }
        match shp::parse_shp(&bytes, path) {
            Ok(desc) => {
                ok += 1;
                // Whatever was accepted satisfies the description's invariants.
                for brep in &desc.breps {
                    assert_eq!(brep.parts.len(), brep.triangles.len());
                    assert!(
                        brep.triangles
                            .iter()
                            .flatten()
                            .all(|&v| (v as usize) < brep.vertices.len())
                    );
                    assert!(brep.parts.iter().all(|&p| p < brep.part_count));
                    assert!(brep.vertices.iter().flatten().all(|c| c.is_finite()));
                }
            }
            Err(e) => {
                err += 1;
                let message = e.to_string();
                assert!(message.starts_with("fuzz.shp: "), "{message}");
                if let Some(line) = e.line() {
                    assert!(
                        message.starts_with(&format!("fuzz.shp: line {line}: ")),
                        "{message}"
                    );
                }
            }
        }
        let _ = shp::parse_brs(&bytes, path, "brs_0");
    }
    eprintln!("{ok} accepted, {err} rejected");
    assert!(
        ok > 500 && err > 5000,
        "{ok} accepted, {err} rejected: the mutations should exercise both"
    );
}
