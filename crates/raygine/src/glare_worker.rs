//! The viewer's glare: UGR and DGP at every observer, judged on a background thread from a
//! fisheye rendered at each eye, refined progressively (4, 16, 64 samples a pixel, each a
//! complete deterministic judgement, as `raygine glare --samples N` gives), restarted when the
//! scene, its setup (the camera aside), the integrator or the glare options change. The UI
//! thread never waits: it polls the latest results.

use crate::background_job::Restartable;
use glam::DVec3;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use tracer_core::glare::{
    GlareFigures, GlareOptions, SampleBatches, check_eye, judge_observer, light_names,
    observer_basis, observer_setup, samples_of, sun_pixels,
};
use tracer_core::integrator::IntegratorKind;
use tracer_core::lit_scene::LitScene;
use tracer_core::render::{Film, RenderSettings, render_pixels};
use tracer_core::scene::{Observer, Scene, Setup};

/// Samples a pixel of the successive refinements, and the fisheye's side (half the command
/// line's, for a quick first answer on one thread: small sources read a little lower).
pub const REFINEMENTS: [u32; 3] = [4, 16, 64];
pub const IMAGE_SIZE: u32 = 400;

/// Samples a pixel rendered between two checks for cancellation.
const CHUNK: u32 = 4;

/// Batches kept for the errors of an integrator that splats: one a sample, neighbours merged
/// in pairs whenever there are more than this.
const MAX_BATCHES: usize = 16;

/// What a judgement depends on.
#[derive(Clone, Debug, PartialEq)]
struct Key {
    scene: usize,
    setup: Setup,
    integrator: IntegratorKind,
    options: GlareOptions,
}

/// One observer's glare, for the panel and the viewport.
#[derive(Clone, Debug)]
pub struct ObserverReading {
    pub name: String,
    /// The figures, or why there are none (an eye inside a solid).
    pub result: Result<Judged, String>,
}

/// The figures of both ways, and what the viewport outlines.
#[derive(Clone, Debug)]
pub struct Judged {
    pub from_image: GlareFigures,
    pub analytic: Option<GlareFigures>,
    /// The observer's frame in the scene: right, up, forward.
    pub frame: [glam::Vec3; 3],
    /// Per image source, the directions (observer frame) of its edge pixels.
    pub outlines: Vec<Vec<DVec3>>,
}

/// The latest finished refinement of the current job.
#[derive(Clone, Debug, Default)]
pub struct GlareReadings {
    pub observers: Vec<ObserverReading>,
    /// Samples a pixel behind them.
    pub samples: u32,
    pub finished: bool,
}

/// Background glare of the current document's observers.
#[derive(Debug, Default)]
pub struct GlareWorker {
    job: Restartable<Key, GlareReadings>,
}

impl GlareWorker {
    /// Starts a new job when what glare depends on changed (none without observers).
    pub fn update(
        &mut self,
        scene: &Arc<Scene>,
        setup: &Setup,
        integrator: IntegratorKind,
        options: GlareOptions,
        ctx: &egui::Context,
    ) {
        // The observers look through their own fisheyes: orbiting must not restart glare.
        let mut without_camera = setup.clone();
        without_camera.camera = tracer_core::scene::Camera::default();
        let key = Key {
            scene: Arc::as_ptr(scene) as usize,
            setup: without_camera,
            integrator,
            options,
        };
        let Some(handles) = self.job.restart(key) else {
            return;
        };
        if setup.observers.is_empty() {
            return;
        }
        let (cancel, latest) = (Arc::clone(&handles.cancel), Arc::clone(&handles.latest));
        let (scene, setup, ctx) = (Arc::clone(scene), setup.clone(), ctx.clone());
        let spawned = std::thread::Builder::new()
            .name("raygine-glare".into())
            .spawn(move || run(&scene, &setup, integrator, options, &cancel, &latest, &ctx));
        if let Err(e) = spawned {
            eprintln!("raygine: cannot start the glare thread: {e}");
        }
    }

    /// The latest readings of the current job (None before the first refinement).
    pub fn readings(&self) -> Option<GlareReadings> {
        self.job.latest()
    }
}

/// The directions of the pixels of `pixels` that have a neighbour outside the set.
fn edge_directions(image: &tracer_core::glare::GlareImage, pixels: &[usize]) -> Vec<DVec3> {
    let w = image.width as usize;
    let set: std::collections::HashSet<usize> = pixels.iter().copied().collect();
    pixels
        .iter()
        .copied()
        .filter(|&i| {
            let (x, y) = (i % w, i / w);
            let outside = |nx: Option<usize>, ny: Option<usize>| match (nx, ny) {
                (Some(nx), Some(ny)) if nx < w && ny < image.height as usize => {
                    !set.contains(&(ny * w + nx))
                }
                _ => true,
            };
            outside(x.checked_sub(1), Some(y))
                || outside(Some(x + 1), Some(y))
                || outside(Some(x), y.checked_sub(1))
                || outside(Some(x), Some(y + 1))
        })
        .map(|i| image.direction[i])
        .collect()
}

/// Judges one observer from `film`, or says why not.
fn judge(
    scene: &Scene,
    setup: &Setup,
    observer: &Observer,
    film: &Film,
    batches: Option<&SampleBatches>,
    options: &GlareOptions,
    max_depth: u32,
) -> Judged {
    let obs_setup = observer_setup(setup, observer);
    let lit = LitScene::new(scene, &obs_setup, max_depth);
    let g = judge_observer(
        &lit,
        &obs_setup,
        observer,
        film,
        batches,
        options,
        &light_names(setup),
    );
    let basis = observer_basis(setup, observer, IMAGE_SIZE);
    let outlines = g
        .from_image
        .sources
        .iter()
        .map(|s| edge_directions(&g.image, &s.pixels))
        .collect();
    Judged {
        from_image: g.from_image,
        analytic: g.analytic,
        frame: [basis.right, basis.up, basis.forward],
        outlines,
    }
}

fn run(
    scene: &Scene,
    setup: &Setup,
    integrator: IntegratorKind,
    options: GlareOptions,
    cancel: &AtomicBool,
    latest: &Mutex<Option<GlareReadings>>,
    ctx: &egui::Context,
) {
    // One worker thread: the picture's render keeps the other cores.
    let Ok(pool) = rayon::ThreadPoolBuilder::new().num_threads(1).build() else {
        return;
    };
    let settings = RenderSettings {
        width: IMAGE_SIZE,
        height: IMAGE_SIZE,
        integrator,
        pixel_illuminance: false,
        ..RenderSettings::default()
    };
    let observers = &setup.observers;
    // Each observer's film so far, and the eyes that cannot see.
    let mut films: Vec<Option<Film>> = vec![None; observers.len()];
    // Where samples splat, each observer's samples also in independent batches, one sample
    // each (merged in pairs beyond MAX_BATCHES): the errors' source (tracer_core::glare::batches).
    let splats = integrator.splats();
    let chunk = if splats { 1 } else { CHUNK };
    let mut batches: Vec<SampleBatches> = vec![SampleBatches::default(); observers.len()];
    // Per observer, once: whether its eye can see, and the pixels the sun may fall in (they
    // take more of their own samples, tracer_core::glare::sun).
    let (eyes, suns): (Vec<Result<(), String>>, Vec<Vec<bool>>) = observers
        .iter()
        .map(|o| {
            let lit = LitScene::new(scene, &observer_setup(setup, o), settings.max_depth);
            let sun = sun_pixels(&lit, &observer_basis(setup, o, IMAGE_SIZE));
            (check_eye(&lit, o), sun)
        })
        .unzip();
    let mut done = 0;
    for (k, &target) in REFINEMENTS.iter().enumerate() {
        for (i, o) in observers.iter().enumerate() {
            if eyes[i].is_err() {
                continue;
            }
            let obs_setup = observer_setup(setup, o);
            let sun = &suns[i];
            let mut at = done;
            while at < target {
                if cancel.load(Ordering::Acquire) {
                    return;
                }
                let end = (at + chunk).min(target);
                let (part, _) = pool.install(|| {
                    render_pixels(scene, &obs_setup, &settings, &|p| {
                        samples_of(p, &(at..end), sun)
                    })
                });
                if splats {
                    batches[i].push_capped(&part, MAX_BATCHES);
                }
                match &mut films[i] {
                    Some(f) => {
                        if f.merge(&part).is_err() {
                            return;
                        }
                    }
                    None => films[i] = Some(part),
                }
                at = end;
            }
        }
        done = target;
        let readings: Vec<ObserverReading> = observers
            .iter()
            .enumerate()
            .map(|(i, o)| ObserverReading {
                name: o.name.clone(),
                result: match (&eyes[i], &films[i]) {
                    (Err(e), _) => Err(e.clone()),
                    (Ok(()), Some(film)) => {
                        let b = splats.then_some(&batches[i]);
                        Ok(pool.install(|| {
                            judge(scene, setup, o, film, b, &options, settings.max_depth)
                        }))
                    }
                    (Ok(()), None) => Err("not rendered".to_owned()),
                },
            })
            .collect();
        if cancel.load(Ordering::Acquire) {
            return;
        }
        if let Ok(mut l) = latest.lock() {
            *l = Some(GlareReadings {
                observers: readings,
                samples: target,
                finished: k + 1 == REFINEMENTS.len(),
            });
        }
        ctx.request_repaint();
    }
}

/// "23.9 ± 0.1", "0.2213 ± 0.0004": at least `decimals` decimals, more until the error shows
/// a significant digit (at most 4).
pub fn plus_minus(value: f64, se: f64, decimals: usize) -> String {
    if !se.is_finite() {
        return format!("{value:.decimals$}");
    }
    let needed = if se > 0.0 {
        (-se.log10().floor()).max(0.0) as usize
    } else {
        decimals
    };
    let d = needed.clamp(decimals, 4);
    if se < 0.5 * 10f64.powi(-(d as i32)) {
        // Too small to show at this precision: say so rather than "± 0.0000".
        return format!("{value:.d$} ± <{:.d$}", 10f64.powi(-(d as i32)));
    }
    format!("{value:.d$} ± {se:.d$}")
}
