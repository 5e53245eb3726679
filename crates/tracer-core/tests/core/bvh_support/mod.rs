//! Helpers shared by the BVH integration tests: a deterministic generator, a minimal reader
//! for the shared `.shp` meshes (test-only; the real parser lives in `shp/`), and ray sets.

#![allow(dead_code)]

use std::path::PathBuf;

use glam::Vec3;
use tracer_core::{Aabb, Ray};

/// xorshift64*: deterministic, no dependencies.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// Uniform in [0, 1).
    pub fn f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }

    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    pub fn in_box(&mut self, b: &Aabb) -> Vec3 {
        let t = Vec3::new(self.f32(), self.f32(), self.f32());
        b.min + (b.max - b.min) * t
    }

    pub fn unit_vector(&mut self) -> Vec3 {
        loop {
            let v = Vec3::new(self.f32(), self.f32(), self.f32()) * 2.0 - 1.0;
            let l = v.length_squared();
            if l > 1e-4 && l <= 1.0 {
                return v / l.sqrt();
            }
        }
    }
}

pub fn bounds_of(triangles: &[[Vec3; 3]]) -> Aabb {
    triangles
        .iter()
        .flatten()
        .fold(Aabb::EMPTY, |b, &p| b.grow(p))
}

/// `../shared` beside the repository, if present.
pub fn shared_dir() -> Option<PathBuf> {
    raygine_fixtures::shared("scenes").and_then(|p| Some(p.parent()?.to_path_buf()))
}

/// The shared meshes as (file stem, triangles), smallest first.
pub fn shared_meshes() -> Vec<(String, Vec<[Vec3; 3]>)> {
    let Some(dir) = shared_dir() else {
        return Vec::new();
    };
    let mut paths: Vec<PathBuf> = std::fs::read_dir(dir.join("scenes/meshes"))
        .map(|rd| rd.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    paths.retain(|p| p.extension().is_some_and(|e| e == "shp"));
    let mut meshes: Vec<(String, Vec<[Vec3; 3]>)> = paths
        .iter()
        .map(|p| {
            let stem = p.file_stem().unwrap().to_string_lossy().into_owned();
            let text = std::fs::read_to_string(p).unwrap();
            (stem, read_mesh(&text))
        })
        .collect();
    meshes.sort_by_key(|m| m.1.len());
    meshes
}

/// Minimal reader: `vertices N` + N lines of 3 floats, `triangles M` + M lines of 3 indices
/// (0-based); `;;` comments and every other line ignored.
pub fn read_mesh(text: &str) -> Vec<[Vec3; 3]> {
    let mut lines = text
        .lines()
        .map(|l| l.split(";;").next().unwrap_or("").trim());
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    while let Some(line) = lines.next() {
        let mut words = line.split_whitespace();
        let (key, count) = (
            words.next(),
            words.next().and_then(|c| c.parse::<usize>().ok()),
        );
        match (key, count) {
            (Some("vertices"), Some(n)) => {
                for l in lines.by_ref().take(n) {
                    let f: Vec<f32> = l.split_whitespace().map(|w| w.parse().unwrap()).collect();
                    vertices.push(Vec3::new(f[0], f[1], f[2]));
                }
            }
            (Some("triangles"), Some(m)) => {
                for l in lines.by_ref().take(m) {
                    let i: Vec<usize> = l.split_whitespace().map(|w| w.parse().unwrap()).collect();
                    triangles.push([vertices[i[0]], vertices[i[1]], vertices[i[2]]]);
                }
            }
            _ => {}
        }
    }
    triangles
}

/// The W1 primary-ray camera of BENCHMARK.md: 1024 x 1024 pixel centres, 45 degree vertical
/// field of view, looking down -Z from `c + (0, 0, r / sin(22.5 deg))`.
pub fn w1_rays(bounds: &Aabb) -> Vec<Ray> {
    const SIZE: usize = 1024;
    let half = 22.5_f32.to_radians();
    let (c, r) = (bounds.center(), bounds.radius());
    let eye = c + Vec3::new(0.0, 0.0, r / half.sin());
    let tan = half.tan();
    let mut rays = Vec::with_capacity(SIZE * SIZE);
    for j in 0..SIZE {
        for i in 0..SIZE {
            let x = (2.0 * (i as f32 + 0.5) / SIZE as f32 - 1.0) * tan;
            let y = (1.0 - 2.0 * (j as f32 + 0.5) / SIZE as f32) * tan;
            rays.push(Ray::new(eye, Vec3::new(x, y, -1.0).normalize()));
        }
    }
    rays
}
