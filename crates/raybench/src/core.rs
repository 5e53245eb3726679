//! `raybench core`: raygine alone on every mesh: BVH build, W1-W3, memory per triangle, and L3
//! (path to a ready scene through `scene::load`).

use std::time::Instant;

use tracer_core::scene::{self, LoadOptions};

use crate::contender::{Lib, measure};
use crate::meshes;
use crate::peers::raygine::Raygine;
use crate::report::{Figure, emit, table};
use crate::stats::median;
use crate::trace::{pool, workloads_for};

#[derive(Clone, Debug)]
pub struct Options {
    pub runs: usize,
    pub threads: Vec<usize>,
    pub meshes: Vec<String>,
}

pub fn run(opts: &Options) -> anyhow::Result<()> {
    let shared = crate::shared::require_shared()?;
    let temp = std::env::temp_dir().join(format!("raybench-{}", std::process::id()));
    let mut figures: Vec<Figure> = Vec::new();
    let mut extra =
        String::from("| mesh | threads | bytes/tri | L3 load ms |\n|---|---|---|---|\n");
    for name in &opts.meshes {
        let mesh = meshes::load(name, &shared)?;
        let workloads = workloads_for(&mesh.triangles)?;
        emit(&format!(
            "# mesh={} triangles={} W1={} W2={} W3={}",
            mesh.name,
            mesh.triangles.len(),
            workloads.w1.len(),
            workloads.w2.len(),
            workloads.w3.len()
        ));
        let shp = meshes::shp_path(&mesh, &temp)?;
        for &threads in &opts.threads {
            let pool = pool(threads)?;
            let mut contenders = vec![Lib::<Raygine>::boxed()];
            figures.extend(measure(
                &mut contenders,
                &pool,
                &mesh.name,
                &mesh.triangles,
                &workloads,
                opts.runs,
            )?);
            let bytes = contenders[0].memory_bytes().unwrap_or(0) as f64;
            let per_tri = bytes / mesh.triangles.len().max(1) as f64;
            emit(&format!(
                "mem mesh={} lib=raygine threads={threads} bytes_per_tri={per_tri:.1}",
                mesh.name
            ));
            drop(contenders);
            let (mut loads, mut parses, mut bvhs) = (Vec::new(), Vec::new(), Vec::new());
            for _ in 0..opts.runs {
                let start = Instant::now();
                let loaded = pool.install(|| scene::load(&shp, &LoadOptions::default()))?;
                loads.push(start.elapsed().as_secs_f64() * 1e3);
                parses.push(loaded.parse_secs * 1e3);
                bvhs.push(loaded.scene.bvh_build_secs * 1e3);
                drop(loaded);
            }
            let load_ms = median(&loads);
            emit(&format!(
                "L3 mesh={} threads={threads} load_ms={load_ms:.0} parse_ms={:.0} bvh_ms={:.0}",
                mesh.name,
                median(&parses),
                median(&bvhs)
            ));
            extra += &format!(
                "| {} | {threads} | {per_tri:.1} | {load_ms:.0} |\n",
                mesh.name
            );
        }
    }
    let _ = std::fs::remove_dir_all(&temp);
    emit(&format!(
        "\n## raygine core (medians of {} runs)\n\n{}\n{extra}",
        opts.runs,
        table(&figures)
    ));
    Ok(())
}
