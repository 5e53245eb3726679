//! The viewer's denoised display: Open Image Denoise on a background thread, over snapshots of
//! the film, within a CPU budget. Only the picture is denoised: hover, meter, grids, false
//! colour and the noise figure read the film's exact sums whether the toggle is on or off.
//!
//! When: after the first full pass, whenever new samples have arrived (a finished pass, a
//! stretch of the next one, a pause or convergence), but never more often than the budget
//! allows: after a denoise that took `c` seconds on `t` threads, the next waits until the
//! denoiser's share of the machine's CPU time since the last one's start is at most
//! [`CPU_SHARE`].

use glam::Vec3;
use std::sync::mpsc::{Receiver, Sender, channel};
use std::sync::{Arc, OnceLock};
use std::time::{Duration, Instant};
use tracer_core::denoise::{Denoiser, Images, Quality};
use tracer_core::integrator::IntegratorKind;

/// The largest share of the CPU time the viewer's denoising may take.
pub const CPU_SHARE: f64 = 0.25;

/// One denoised picture of a generation.
#[derive(Debug)]
pub struct Picture {
    pub generation: u64,
    pub width: u32,
    pub height: u32,
    /// Denoised colour, cd/m² per channel, row-major.
    pub rgb: Vec<Vec3>,
    /// Seconds the denoise took.
    pub secs: f64,
    /// Full samples per pixel the picture was made from (the fewest of any pixel).
    pub samples: u32,
}

struct Job {
    generation: u64,
    width: u32,
    height: u32,
    color: Vec<Vec3>,
    albedo: Vec<Vec3>,
    normal: Vec<Vec3>,
    samples: u32,
}

enum Reply {
    Ready(Result<String, String>),
    Done(Result<Picture, String>),
}

/// The process's denoiser, loaded once (the first viewer's thread loads it).
fn shared_denoiser(threads: usize) -> &'static Result<Arc<Denoiser>, String> {
    static DENOISER: OnceLock<Result<Arc<Denoiser>, String>> = OnceLock::new();
    DENOISER.get_or_init(|| {
        Denoiser::load(threads)
            .map(Arc::new)
            .map_err(|e| e.to_string())
    })
}

/// Whether the denoiser can be used, as far as the viewer knows.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Availability {
    Loading,
    /// Ready: "Open Image Denoise 2.5.1".
    Ready(String),
    /// Why not, in one line.
    Unavailable(String),
}

pub struct DenoiseView {
    /// The toggle, per kind of transport: on in the GI modes, off in Direct, by default.
    pub on_gi: bool,
    pub on_direct: bool,
    pub availability: Availability,
    jobs: Sender<Job>,
    replies: Receiver<Reply>,
    in_flight: bool,
    /// The newest picture, of whichever generation.
    pub picture: Option<Arc<Picture>>,
    /// The last denoise's start, its wall time and threads (for the budget).
    last_started: Option<Instant>,
    last_secs: f64,
    threads: usize,
    /// Rays traced in the generation when the last job was sent (new samples since?).
    last_rays: Option<(u64, u64)>,
    /// The last error while denoising (shown once in the status bar).
    pub error: Option<String>,
}

impl std::fmt::Debug for DenoiseView {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DenoiseView")
            .field("availability", &self.availability)
            .field("on_gi", &self.on_gi)
            .finish_non_exhaustive()
    }
}

impl DenoiseView {
    /// Starts the denoise thread, which loads OIDN (with `threads` threads) in the background.
    pub fn new(ctx: &egui::Context, threads: usize) -> Self {
        let (jobs, job_rx) = channel::<Job>();
        let (reply_tx, replies) = channel::<Reply>();
        let ctx = ctx.clone();
        let spawned = std::thread::Builder::new()
            .name("denoise".to_owned())
            .spawn(move || serve(&ctx, threads, &job_rx, &reply_tx));
        let availability = match spawned {
            Ok(_) => Availability::Loading,
            Err(e) => Availability::Unavailable(format!("cannot start the denoise thread: {e}")),
        };
        Self {
            on_gi: true,
            on_direct: false,
            availability,
            jobs,
            replies,
            in_flight: false,
            picture: None,
            last_started: None,
            last_secs: 0.0,
            threads: threads.max(1),
            last_rays: None,
            error: None,
        }
    }

    /// The toggle for `mode`.
    pub fn wanted(&self, mode: IntegratorKind) -> bool {
        if mode == IntegratorKind::Direct {
            self.on_direct
        } else {
            self.on_gi
        }
    }

    /// Flips the toggle for `mode` (D).
    pub fn toggle(&mut self, mode: IntegratorKind) {
        if mode == IntegratorKind::Direct {
            self.on_direct = !self.on_direct;
        } else {
            self.on_gi = !self.on_gi;
        }
    }

    pub fn available(&self) -> bool {
        matches!(self.availability, Availability::Ready(_))
    }

    /// Whether renders should trace the guides: wherever the toggle may show a denoised
    /// picture without a restart (the GI modes), or where it is on.
    pub fn guides_wanted(&self, mode: IntegratorKind) -> bool {
        !matches!(self.availability, Availability::Unavailable(_))
            && (mode != IntegratorKind::Direct || self.on_direct)
    }

    /// The picture to show instead of the raw film, if one of `generation` is ready and wanted.
    pub fn shown(&self, generation: u64, mode: IntegratorKind) -> Option<&Arc<Picture>> {
        self.picture
            .as_ref()
            .filter(|p| p.generation == generation && self.wanted(mode) && self.available())
    }

    /// Picks up finished work, and sends the next job when one is due (see the module docs).
    /// Returns how long to wait before asking again when new samples wait for the budget.
    pub fn poll(
        &mut self,
        worker: &crate::render_worker::RenderWorker,
        mode: IntegratorKind,
    ) -> Option<Duration> {
        while let Ok(reply) = self.replies.try_recv() {
            match reply {
                Reply::Ready(Ok(version)) => self.availability = Availability::Ready(version),
                Reply::Ready(Err(why)) => self.availability = Availability::Unavailable(why),
                Reply::Done(result) => {
                    self.in_flight = false;
                    match result {
                        Ok(p) => {
                            self.last_secs = p.secs;
                            self.picture = Some(Arc::new(p));
                        }
                        Err(e) => self.error = Some(e),
                    }
                }
            }
        }
        if self.in_flight || !self.available() || !self.wanted(mode) {
            return None;
        }
        let stats = worker.stats();
        let generation = worker.generation();
        if stats.generation != generation || stats.samples_per_pixel == 0 {
            return None;
        }
        if self.last_rays == Some((generation, stats.rays)) {
            return None;
        }
        let new_generation = self.last_rays.is_none_or(|(g, _)| g != generation);
        if let (Some(t), false) = (self.last_started, new_generation) {
            // Denoiser CPU time over machine CPU time since the last start: c t / (T n).
            let cores = std::thread::available_parallelism().map_or(1, |n| n.get()) as f64;
            let used = self.last_secs * self.threads as f64 / cores;
            let due = used / CPU_SHARE;
            let elapsed = t.elapsed().as_secs_f64();
            if elapsed < due {
                return Some(Duration::from_secs_f64((due - elapsed).max(0.05)));
            }
        }
        let job = worker.with_film(|f| {
            let f = f.filter(|f| f.generation == generation)?;
            let guides = f.accum.guides.as_ref()?;
            Some(Job {
                generation,
                width: f.width(),
                height: f.height(),
                color: f.shown_rgb_all(),
                albedo: guides.albedo_image(),
                normal: guides.normal_image(),
                samples: f.accum.min_samples(),
            })
        });
        let job = job?;
        if self.jobs.send(job).is_ok() {
            self.in_flight = true;
            self.last_started = Some(Instant::now());
            self.last_rays = Some((generation, stats.rays));
        }
        None
    }
}

/// The denoise thread: loads OIDN, then denoises job after job. Prefiltered guides are kept
/// and made again only for a new generation or when the samples behind them have doubled.
fn serve(ctx: &egui::Context, threads: usize, jobs: &Receiver<Job>, replies: &Sender<Reply>) {
    let denoiser = match shared_denoiser(threads) {
        Ok(d) => {
            let _ = replies.send(Reply::Ready(Ok(format!(
                "Open Image Denoise {}",
                d.version_text()
            ))));
            Arc::clone(d)
        }
        Err(why) => {
            let _ = replies.send(Reply::Ready(Err(why.clone())));
            ctx.request_repaint();
            return;
        }
    };
    ctx.request_repaint();
    let mut clean: Option<(u64, u32, Vec<Vec3>, Vec<Vec3>)> = None;
    while let Ok(mut job) = jobs.recv() {
        // Only the newest job counts.
        while let Ok(newer) = jobs.try_recv() {
            job = newer;
        }
        let started = Instant::now();
        let result = denoise_job(&denoiser, &job, &mut clean).map(|rgb| Picture {
            generation: job.generation,
            width: job.width,
            height: job.height,
            rgb,
            secs: started.elapsed().as_secs_f64(),
            samples: job.samples,
        });
        if replies.send(Reply::Done(result)).is_err() {
            return;
        }
        ctx.request_repaint();
    }
}

fn denoise_job(
    denoiser: &Denoiser,
    job: &Job,
    clean: &mut Option<(u64, u32, Vec<Vec3>, Vec<Vec3>)>,
) -> Result<Vec<Vec3>, String> {
    let images = Images {
        width: job.width,
        height: job.height,
        color: &job.color,
        albedo: &job.albedo,
        normal: &job.normal,
    };
    let stale = clean.as_ref().is_none_or(|(g, n, a, _)| {
        *g != job.generation || job.samples >= n.saturating_mul(2) || a.len() != job.color.len()
    });
    if stale {
        let (a, n) = denoiser
            .prefilter(&images, Quality::Balanced)
            .map_err(|e| e.to_string())?;
        *clean = Some((job.generation, job.samples.max(1), a, n));
    }
    let Some((_, _, albedo, normal)) = clean.as_ref() else {
        return Err("no guides".to_owned());
    };
    denoiser
        .denoise_clean(
            &Images {
                albedo,
                normal,
                ..images
            },
            Quality::Balanced,
        )
        .map_err(|e| e.to_string())
}
