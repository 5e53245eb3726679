//! The viewer's side of the render engine: starts a new generation whenever the scene, its setup
//! or the render settings change, and keeps a GPU texture of the film through the display mapping,
//! uploading only the tiles that changed. Never blocks the UI thread for long: the film lock is
//! held only while a changed rectangle is mapped.

use crate::denoise_view::Picture;
use egui::{ColorImage, TextureHandle, TextureOptions};
use glam::Vec3;
use std::sync::Arc;
use std::time::{Duration, Instant};
use tracer_core::display::{DisplayMapper, DisplaySettings};
use tracer_core::render::{
    ProgressiveFilm, RenderSession, RenderSettings, SessionStats, Snapshot, Tile,
};
use tracer_core::scene::{CameraBasis, Scene, Setup};

/// What the current generation renders; a change restarts the render.
#[derive(Clone, Debug)]
pub struct RenderKey {
    pub scene: Arc<Scene>,
    pub setup: Setup,
    pub settings: RenderSettings,
    pub threads: usize,
    /// Adaptive sampling after the first samples (see `Snapshot::adaptive`).
    pub adaptive: bool,
}

impl PartialEq for RenderKey {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.scene, &other.scene)
            && self.setup == other.setup
            && self.settings == other.settings
            && self.threads == other.threads
            && self.adaptive == other.adaptive
    }
}

pub struct RenderWorker {
    session: RenderSession,
    current: Option<RenderKey>,
    texture: Option<TextureHandle>,
    /// Generation and display mapping the texture shows.
    shown_generation: u64,
    shown_display: Option<DisplaySettings>,
    shown_exposure: f32,
    shown_passes: u32,
    /// The display mapping in force (made again when the settings or the exposure change).
    mapper: Option<DisplayMapper>,
    /// When the current generation was started (for change-to-pixels latency).
    started_at: Option<Instant>,
    /// Seconds from the last restart to the first texture upload of the new generation.
    pub last_change_to_pixels: Option<f64>,
    /// The first generation of the current scene: older films show another scene and are never
    /// drawn (a scene opened while paused, or before its first preview lands).
    scene_first_generation: u64,
    /// The denoised picture to show instead of the film's means (see `denoise_view`), and
    /// whether the texture must be remapped for a change of it.
    denoised: Option<Arc<Picture>>,
    denoised_changed: bool,
}

impl std::fmt::Debug for RenderWorker {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RenderWorker")
            .field("shown_generation", &self.shown_generation)
            .finish_non_exhaustive()
    }
}

impl RenderWorker {
    pub fn new(ctx: &egui::Context, threads: usize) -> std::io::Result<Self> {
        let repaint = ctx.clone();
        // New tiles wake the UI, but at most about 30 times a second: every frame also costs the
        // (often software) OpenGL renderer, which competes with the render threads.
        let session = RenderSession::new(
            threads,
            Arc::new(move || repaint.request_repaint_after(Duration::from_millis(33))),
        )?;
        Ok(Self {
            session,
            current: None,
            texture: None,
            shown_generation: 0,
            shown_display: None,
            shown_exposure: 0.0,
            shown_passes: 0,
            mapper: None,
            started_at: None,
            last_change_to_pixels: None,
            scene_first_generation: 0,
            denoised: None,
            denoised_changed: false,
        })
    }

    /// Shows `picture` (a denoised picture of the current generation) instead of the film's
    /// means, or the means again for None.
    pub fn set_denoised(&mut self, picture: Option<Arc<Picture>>) {
        let same = match (&self.denoised, &picture) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (None, None) => true,
            _ => false,
        };
        if !same {
            self.denoised = picture;
            self.denoised_changed = true;
        }
    }

    /// The denoised picture the texture shows, if any.
    pub fn denoised_shown(&self) -> Option<&Arc<Picture>> {
        self.denoised.as_ref()
    }

    /// Starts a new generation when `key` differs from the running one. Returns whether it did.
    pub fn sync(&mut self, key: RenderKey) -> bool {
        if self.current.as_ref() == Some(&key) {
            return false;
        }
        self.session.set_threads(key.threads);
        let new_scene = self
            .current
            .as_ref()
            .is_none_or(|k| !Arc::ptr_eq(&k.scene, &key.scene));
        let generation = self.session.start(Snapshot {
            scene: Arc::clone(&key.scene),
            setup: key.setup.clone(),
            settings: key.settings,
            time_limit: None,
            adaptive: key.adaptive,
        });
        if new_scene {
            self.scene_first_generation = generation;
        }
        self.current = Some(key);
        self.started_at = Some(Instant::now());
        true
    }

    pub fn generation(&self) -> u64 {
        self.session.generation()
    }

    /// The generation the texture shows.
    pub fn shown_generation(&self) -> u64 {
        self.shown_generation
    }

    /// The first generation of the scene being rendered.
    pub fn scene_first_generation(&self) -> u64 {
        self.scene_first_generation
    }

    /// Whether the texture shows the current scene (a film of it has been uploaded).
    pub fn shows_current_scene(&self) -> bool {
        self.texture.is_some() && self.shown_generation >= self.scene_first_generation
    }

    pub fn stats(&self) -> SessionStats {
        self.session.stats()
    }

    /// Measure the pixels' illuminance from the next pass on (see
    /// `RenderSession::measure_illuminance`).
    pub fn measure_illuminance(&self) {
        self.session.measure_illuminance();
    }

    pub fn set_paused(&self, paused: bool) {
        self.session.set_paused(paused);
    }

    /// The key of the generation running, with its camera basis (for picking and markers).
    pub fn current(&self) -> Option<&RenderKey> {
        self.current.as_ref()
    }

    pub fn basis(&self) -> Option<CameraBasis> {
        self.current.as_ref().map(|k| {
            k.setup
                .camera
                .basis(k.setup.handedness, k.settings.width, k.settings.height)
        })
    }

    /// Reads the film (the session's lock is held during `f`).
    pub fn with_film<R>(&self, f: impl FnOnce(Option<&ProgressiveFilm>) -> R) -> R {
        self.session.with_film(f)
    }

    /// Brings the texture up to date: changed tiles only, or everything after a new generation
    /// or a change of the display mapping. Returns the texture to draw, if any: never one of
    /// another scene.
    pub fn update_texture(
        &mut self,
        ctx: &egui::Context,
        display: &DisplaySettings,
        scene: &Arc<Scene>,
    ) -> Option<&TextureHandle> {
        self.refresh_texture(ctx, display);
        let renders_scene = self
            .current
            .as_ref()
            .is_some_and(|k| Arc::ptr_eq(&k.scene, scene));
        if renders_scene && self.shows_current_scene() {
            self.texture.as_ref()
        } else {
            None
        }
    }

    fn refresh_texture(&mut self, ctx: &egui::Context, display: &DisplaySettings) {
        let dirty = self.session.take_dirty();
        let stats = self.session.stats();
        let generation = self.session.with_film(|f| f.map(|f| f.generation));
        let Some(generation) = generation else {
            return;
        };
        let new_generation = generation != self.shown_generation;
        // Auto exposure follows the image as it refines: re-check it after each pass.
        let exposure_stale = display.auto_exposure && stats.passes_done != self.shown_passes;
        let mut exposure = self.shown_exposure;
        if new_generation || exposure_stale || self.shown_display.as_ref() != Some(display) {
            exposure = self
                .session
                .with_film(|f| f.map(|f| exposure_stops(display, f)))
                .unwrap_or(0.0);
        }
        // A denoised picture of this generation, of this size, replaces the means.
        let denoised = self
            .denoised
            .as_ref()
            .filter(|p| p.generation == generation)
            .filter(|p| {
                self.current
                    .as_ref()
                    .is_some_and(|k| (k.settings.width, k.settings.height) == (p.width, p.height))
            })
            .cloned();
        let full = new_generation
            || std::mem::take(&mut self.denoised_changed)
            || self.shown_display.as_ref() != Some(display)
            || (exposure - self.shown_exposure).abs() > 0.02
            || self.texture.is_none();
        self.shown_passes = stats.passes_done;
        if !self
            .mapper
            .as_ref()
            .is_some_and(|m| m.is_for(display, exposure))
        {
            self.mapper = Some(DisplayMapper::new(display, exposure));
        }
        let Some(mapper) = &self.mapper else {
            return;
        };
        if full {
            let colours = denoised.as_ref().map(|p| p.rgb.as_slice());
            let image = self.session.with_film(|f| {
                f.map(|f| texture_rect(f, display, exposure, None, Some(mapper), colours))
            });
            let Some(image) = image else {
                return;
            };
            match &mut self.texture {
                Some(t) if t.size() == image.size => t.set(image, TextureOptions::NEAREST),
                _ => {
                    self.texture = Some(ctx.load_texture("film", image, TextureOptions::NEAREST));
                }
            }
            self.shown_display = Some(*display);
            self.shown_exposure = exposure;
            if new_generation {
                self.shown_generation = generation;
                if let Some(t) = self.started_at.take() {
                    self.last_change_to_pixels = Some(t.elapsed().as_secs_f64());
                }
            }
        } else if let Some(texture) = self.texture.as_mut().filter(|_| denoised.is_none()) {
            // (A denoised picture stays as it is until the next one: new samples change the
            // readouts at once, the picture with the next denoise.)
            // One look at the film for all the rectangles, and only if it is still the film
            // they were taken from and the texture's size: a new generation (a resize) can
            // replace it between `take_dirty` and here, and then the next frame redraws it all.
            let size = texture.size();
            let images = self.session.with_film(|f| {
                let Some(f) = f.filter(|f| {
                    f.generation == generation && [f.width() as usize, f.height() as usize] == size
                }) else {
                    return Vec::new();
                };
                merge_rows(dirty)
                    .into_iter()
                    .filter(|r| r.x0 < r.x1 && r.y0 < r.y1)
                    .filter(|r| r.x1 <= f.width() && r.y1 <= f.height())
                    .map(|rect| {
                        let image =
                            texture_rect(f, display, exposure, Some(rect), Some(mapper), None);
                        (rect, image)
                    })
                    .collect()
            });
            for (rect, image) in images {
                texture.set_partial(
                    [rect.x0 as usize, rect.y0 as usize],
                    image,
                    TextureOptions::NEAREST,
                );
            }
        }
    }

    /// True while the engine still has work to do for the current generation.
    pub fn busy(&self) -> bool {
        let s = self.session.stats();
        let done = s.finished && s.generation == self.session.generation();
        !(done || s.paused)
    }

    /// Waits (for tests and scripts) until the current generation is shown and finished.
    pub fn wait_finished(&self, timeout: Duration) -> bool {
        let generation = self.session.generation();
        self.session
            .wait_for(timeout, |s| s.generation == generation && s.finished)
    }
}

/// The exposure (stops) the film is shown at: the automatic one when enabled.
pub fn exposure_stops(display: &DisplaySettings, film: &ProgressiveFilm) -> f32 {
    if display.auto_exposure {
        tracer_core::display::auto_exposure_stops(&film.shown())
    } else {
        display.exposure_stops
    }
}

/// What the viewport shows of a rectangle of the film (all of it for `None`): its display
/// mapping (through `mapper` when one made for `display` at `exposure` is at hand) with the
/// backdrop where the camera saw nothing. Exports use [`map_rect`] instead. With `colours` (a
/// denoised picture, one per pixel), those are shown instead of the film's means.
pub fn texture_rect(
    film: &ProgressiveFilm,
    display: &DisplaySettings,
    exposure: f32,
    rect: Option<Tile>,
    mapper: Option<&DisplayMapper>,
    colours: Option<&[Vec3]>,
) -> ColorImage {
    let made;
    let mapper = match mapper {
        Some(m) => m,
        None => {
            made = DisplayMapper::new(display, exposure);
            &made
        }
    };
    let mut image = map_rect_with(film, mapper, rect, colours);
    crate::backdrop::draw(&mut image, film, mapper, rect);
    image
}

/// Maps a rectangle of the film (all of it for `None`) to display pixels at `exposure` stops,
/// as exports write them (no backdrop); `colours` as in [`texture_rect`].
pub fn map_rect(
    film: &ProgressiveFilm,
    display: &DisplaySettings,
    exposure: f32,
    rect: Option<Tile>,
    colours: Option<&[Vec3]>,
) -> ColorImage {
    map_rect_with(film, &DisplayMapper::new(display, exposure), rect, colours)
}

/// [`map_rect`] through a mapping already made: the one display path of
/// [`tracer_core::display`], which the CLI and the exports use too.
pub fn map_rect_with(
    film: &ProgressiveFilm,
    mapper: &DisplayMapper,
    rect: Option<Tile>,
    colours: Option<&[Vec3]>,
) -> ColorImage {
    let colours = colours.filter(|c| c.len() == film.accum.len());
    let rect = rect.unwrap_or(Tile {
        x0: 0,
        y0: 0,
        x1: film.width(),
        y1: film.height(),
    });
    let pixels = rect
        .pixels()
        .map(|(x, y)| {
            let i = film.accum.index(x, y);
            let rgb = colours.map_or_else(|| film.shown_rgb(i), |c| c[i]);
            let [r, g, b, _] = mapper.map(rgb, film.shown_illuminance(i));
            egui::Color32::from_rgb(r, g, b)
        })
        .collect();
    ColorImage::new([rect.width() as usize, rect.height() as usize], pixels)
}

/// Fewer, larger uploads: dirty tiles are uploaded one by one, except when there are many,
/// then their bounding box is uploaded once.
fn merge_rows(mut dirty: Vec<Tile>) -> Vec<Tile> {
    if dirty.len() <= 16 {
        return dirty;
    }
    let first = dirty.remove(0);
    let bbox = dirty.iter().fold(first, |a, t| Tile {
        x0: a.x0.min(t.x0),
        y0: a.y0.min(t.y0),
        x1: a.x1.max(t.x1),
        y1: a.y1.max(t.y1),
    });
    vec![bbox]
}
