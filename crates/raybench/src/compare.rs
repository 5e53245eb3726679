//! `raybench compare`: raygine beside the reference libraries compiled in (features `obvhs`,
//! `embree`), same triangles, same rays, same process, interleaved runs; the table of ratios and
//! the geometric mean of raygine/Embree Mrays/s.

use anyhow::bail;

use crate::contender::{Contender, Lib, measure};
use crate::meshes;
use crate::peers::raygine::Raygine;
use crate::report::{Figure, emit, find, speed_ratio, table};
use crate::stats::geometric_mean;
use crate::trace::{pool, workloads_for};

/// raygine first, then every peer compiled in.
fn contenders() -> Vec<Box<dyn Contender>> {
    #[allow(unused_mut)]
    let mut list = vec![Lib::<Raygine>::boxed()];
    #[cfg(feature = "obvhs")]
    list.push(Lib::<crate::peers::obvhs::Obvhs>::boxed());
    #[cfg(feature = "embree")]
    list.push(Lib::<crate::peers::embree::Embree>::boxed());
    list
}

pub fn run(opts: &crate::core::Options) -> anyhow::Result<()> {
    let shared = crate::shared::require_shared()?;
    let mut contenders = contenders();
    if contenders.len() < 2 {
        bail!("no reference library compiled in: build with --features embree,obvhs");
    }
    let mut figures: Vec<Figure> = Vec::new();
    for name in &opts.meshes {
        let mesh = meshes::load(name, &shared)?;
        let workloads = workloads_for(&mesh.triangles)?;
        for &threads in &opts.threads {
            let pool = pool(threads)?;
            figures.extend(measure(
                &mut contenders,
                &pool,
                &mesh.name,
                &mesh.triangles,
                &workloads,
                opts.runs,
            )?);
            contenders.iter_mut().for_each(|c| c.clear());
        }
    }
    let mut summary = format!(
        "\n## raygine vs reference libraries (medians of {} interleaved runs; ratios > 1: raygine faster)\n\n{}",
        opts.runs,
        table(&figures)
    );
    for peer in contenders.iter().skip(1).map(|c| c.lib()) {
        let ratios: Vec<f64> = figures
            .iter()
            .filter(|f| f.lib == "raygine" && !f.is_time())
            .filter_map(|own| {
                find(&figures, &own.kind, &own.mesh, peer, own.threads)
                    .map(|other| speed_ratio(own, other))
            })
            .collect();
        let min = ratios.iter().copied().fold(f64::INFINITY, f64::min);
        let line = format!(
            "geomean lib={peer} figures={} raygine_over_peer_mrays={:.3} min_ratio={min:.3}",
            ratios.len(),
            geometric_mean(&ratios)
        );
        summary += &format!("\n{line}");
    }
    emit(&summary);
    Ok(())
}
