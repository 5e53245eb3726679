//! The viewer's measurements: the scene's grids measured on a background thread, refined
//! progressively (16, 64, 256, 1024, 4096 samples a point, each a complete deterministic
//! measurement, as `raygine measure --samples N` would give), restarted when the scene, its setup
//! or the integrator changes. The UI thread never waits: it polls the latest results. With the
//! daylight factor asked for, the grids are measured under the CIE overcast sky alone
//! (`tracer_core::measure::DaylightFactorSetup`) and read in % of the open horizontal.

use crate::background_job::Restartable;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use tracer_core::integrator::IntegratorKind;
use tracer_core::measure::{
    DaylightFactorSetup, GridResult, MeasureSettings, measure_grids_with_progress,
};
use tracer_core::scene::{Scene, Setup};

/// Samples a point of the successive refinements.
pub const REFINEMENTS: [u32; 5] = [16, 64, 256, 1024, 4096];

/// What a measurement depends on.
#[derive(Clone, Debug, PartialEq)]
struct Key {
    scene: usize,
    setup: Setup,
    integrator: IntegratorKind,
    daylight_factor: bool,
}

/// The latest finished refinement of the current job.
#[derive(Clone, Debug, Default)]
pub struct Readings {
    pub results: Vec<GridResult>,
    /// Samples a point behind `results`.
    pub samples: u32,
    /// Whether the last refinement is done.
    pub finished: bool,
    /// Daylight factors: the readings are in % of the open horizontal (no maintenance factor).
    pub daylight_factor: bool,
    /// Why there are no readings (a daylight factor the scene cannot give).
    pub error: Option<String>,
}

/// Background measurement of the current document's grids.
#[derive(Debug, Default)]
pub struct MeasureWorker {
    job: Restartable<Key, Readings>,
}

impl MeasureWorker {
    /// Starts a new job when what the grids depend on changed (none without grids).
    pub fn update(
        &mut self,
        scene: &Arc<Scene>,
        setup: &Setup,
        integrator: IntegratorKind,
        daylight_factor: bool,
        ctx: &egui::Context,
    ) {
        // Sensors do not depend on the camera: orbiting must not restart the measurement.
        let mut without_camera = setup.clone();
        without_camera.camera = tracer_core::scene::Camera {
            position: [0.0; 3],
            look_at: [0.0; 3],
            up: [0.0; 3],
            fov_deg: 0.0,
            ..Default::default()
        };
        let key = Key {
            scene: Arc::as_ptr(scene) as usize,
            setup: without_camera,
            integrator,
            daylight_factor,
        };
        let Some(handles) = self.job.restart(key) else {
            return;
        };
        if setup.grids.is_empty() {
            return;
        }
        // What is measured: the setup, or its daylight-factor setup (% of E_out,h).
        let (setup, df_scale) = if daylight_factor {
            match DaylightFactorSetup::new(setup) {
                Ok(df) => (df.setup, Some(100.0 / df.outdoor_lx)),
                Err(e) => {
                    handles.publish(Readings {
                        error: Some(e),
                        daylight_factor: true,
                        ..Readings::default()
                    });
                    return;
                }
            }
        } else {
            (setup.clone(), None)
        };
        let (scene, ctx) = (Arc::clone(scene), ctx.clone());
        let (cancel, latest) = (Arc::clone(&handles.cancel), Arc::clone(&handles.latest));
        let job = Job {
            integrator,
            df_scale,
        };
        let spawned = std::thread::Builder::new()
            .name("raygine-measure".into())
            .spawn(move || run(&scene, &setup, job, &cancel, &latest, &ctx));
        if let Err(e) = spawned {
            // Shown in the panel instead of readings.
            handles.publish(Readings::default());
            eprintln!("raygine: cannot start the measurement thread: {e}");
        }
    }

    /// The latest readings of the current job (None before the first refinement).
    pub fn readings(&self) -> Option<Readings> {
        self.job.latest()
    }
}

/// How a job measures: its integrator, and for daylight factors the scale from lx to %.
#[derive(Clone, Copy, Debug)]
struct Job {
    integrator: IntegratorKind,
    df_scale: Option<f64>,
}

fn run(
    scene: &Scene,
    setup: &Setup,
    job: Job,
    cancel: &AtomicBool,
    latest: &Mutex<Option<Readings>>,
    ctx: &egui::Context,
) {
    // One worker thread: the picture's render keeps the other cores.
    let Ok(pool) = rayon::ThreadPoolBuilder::new().num_threads(1).build() else {
        return;
    };
    for (k, &samples) in REFINEMENTS.iter().enumerate() {
        let settings = MeasureSettings {
            integrator: job.integrator,
            max_bounces: None,
            samples,
            time_limit: None,
            target_error: None,
        };
        let results = pool.install(|| {
            measure_grids_with_progress(scene, setup, &settings, &mut |_| {
                !cancel.load(Ordering::Acquire)
            })
        });
        if cancel.load(Ordering::Acquire) {
            return;
        }
        // Maintained illuminance, or daylight factors in %.
        let scale = job.df_scale.unwrap_or(f64::from(setup.maintenance_factor));
        if let Ok(mut l) = latest.lock() {
            *l = Some(Readings {
                results: results.into_iter().map(|r| r.scaled(scale)).collect(),
                samples,
                finished: k + 1 == REFINEMENTS.len(),
                daylight_factor: job.df_scale.is_some(),
                error: None,
            });
        }
        ctx.request_repaint();
    }
}
