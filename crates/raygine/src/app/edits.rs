//! Structural edits of the scene's setup: lights and luminaires added and removed, an
//! environment map read, surfaces hidden and shown, grids added, replaced and removed. Panels
//! ask for them as
//! [`Edit`]s; they are carried out here, and the frame's end records each as one undo step,
//! as it does a finished slider drag.

use super::RaygineApp;
use crate::command::Edit;
use crate::file_ops::Job;
use std::path::PathBuf;
use std::sync::Arc;
use tracer_core::light::{Environment, EnvironmentMap, EnvironmentSource, Luminaire, Photometry};
use tracer_core::measure::placement::{grid_on_surface, work_plane};
use tracer_core::scene::{
    Light, LuminairePlacement, default_light, luminaire_near_surface, luminaire_shape,
};

/// A luminaire file being read on a background job.
#[derive(Debug)]
pub struct PendingLuminaire {
    pub path: PathBuf,
    job: Job<Photometry>,
}

/// An environment map being read on a background job (a 50 MB map takes a while): the map and
/// its notes (texels read as 0).
pub type PendingEnvironmentMap = Job<(EnvironmentMap, Vec<String>)>;

impl RaygineApp {
    /// Carries out one structural edit.
    pub fn edit(&mut self, edit: Edit) {
        let setup = &mut self.doc.setup;
        match edit {
            Edit::AddLight => {
                let mut light = default_light(&self.doc.scene, setup.unit, setup.camera.position);
                light.position =
                    beside_lights(light.position, &setup.lights, &self.doc.scene.bounds);
                setup.lights.push(light);
            }
            Edit::RemoveLight(i) => {
                if i < setup.lights.len() {
                    setup.lights.remove(i);
                }
            }
            Edit::AddLuminaire(path) => {
                let p = path.clone();
                let job = Job::start(
                    "raygine-luminaire",
                    "reading the luminaire",
                    &self.ctx,
                    move || tracer_core::formats::read_photometry(&p).map_err(|e| e.to_string()),
                );
                self.adding_luminaire = Some(PendingLuminaire { path, job });
            }
            Edit::LoadEnvironmentMap(path) => {
                self.loading_environment = Some(Job::start(
                    "raygine-envmap",
                    "reading the environment map",
                    &self.ctx,
                    move || EnvironmentMap::load(&path),
                ));
            }
            Edit::SetHidden { slots, hidden } => {
                for s in slots {
                    if let Some(h) = setup.hidden.get_mut(s as usize) {
                        *h = hidden;
                    }
                }
            }
            Edit::ShowAll => setup.hidden.iter_mut().for_each(|h| *h = false),
            Edit::AddWorkPlane => {
                let unit = setup.unit;
                match work_plane(
                    &self.doc.scene,
                    unit.metres_per_unit(),
                    unit.symbol(),
                    &setup.grids,
                ) {
                    Ok((grid, note)) => {
                        setup.grids.push(grid);
                        self.notice = note;
                    }
                    Err(e) => self.error = Some(e),
                }
            }
            Edit::AddGridOnSurface(slot) => {
                let eye = glam::Vec3::from(setup.camera.position);
                let mpu = setup.unit.metres_per_unit();
                match grid_on_surface(&self.doc.scene, slot, eye, mpu, &setup.grids) {
                    Ok(grid) => setup.grids.push(grid),
                    Err(e) => self.error = Some(e),
                }
            }
            Edit::ReplaceGrid(i, grid) => {
                if let Some(g) = setup.grids.get_mut(i) {
                    *g = *grid;
                }
            }
            Edit::RemoveGrid(i) => {
                if i < setup.grids.len() {
                    setup.grids.remove(i);
                }
            }
        }
    }

    /// Adds the luminaire whose file has been read (or says why not), and warns at once when its
    /// file's opening is a shape raygine does not draw (it becomes a point), or when, drawn as
    /// a point, it hangs closer to a surface than its far field reaches.
    pub(super) fn poll_luminaire(&mut self) {
        let Some(result) = self.adding_luminaire.as_ref().and_then(|p| p.job.poll()) else {
            return;
        };
        let Some(pending) = self.adding_luminaire.take() else {
            return;
        };
        match result {
            Ok(photometry) => {
                let setup = &mut self.doc.setup;
                let base = default_light(&self.doc.scene, setup.unit, setup.camera.position);
                let position = beside_lights(base.position, &setup.lights, &self.doc.scene.bounds);
                let luminaire = std::sync::Arc::new(Luminaire::new(photometry, pending.path));
                setup.lights.push(Light {
                    color: base.color,
                    ..Light::luminaire(position, LuminairePlacement::new(luminaire))
                });
                self.error = None;
                let index = setup.lights.len() - 1;
                let notes = [
                    luminaire_near_surface(&self.doc.scene, setup, index),
                    luminaire_shape(setup, index),
                ];
                for note in notes.into_iter().flatten() {
                    self.notice = Some(note.clone());
                    self.doc.warnings.push(note);
                }
            }
            Err(e) => self.error = Some(e),
        }
    }

    /// Whether a luminaire file is being read.
    pub fn adding_luminaire(&self) -> bool {
        self.adding_luminaire.is_some()
    }

    /// Makes the map that has been read the environment, keeping the turn, the background
    /// choice and (from a map before it) the scale; or says why it could not be read and keeps
    /// the environment there was.
    pub(super) fn poll_environment_map(&mut self) {
        let Some(result) = self.loading_environment.as_ref().and_then(Job::poll) else {
            return;
        };
        self.loading_environment = None;
        let (map, notes) = match result {
            Ok(read) => read,
            Err(e) => {
                self.error = Some(e);
                return;
            }
        };
        let previous = self.doc.setup.environment.as_ref();
        let map = match previous.map(|e| &e.source) {
            // The same file read again, unchanged: the map already shared stays (setups compare
            // a shared map without reading its texels).
            Some(EnvironmentSource::Map(shown)) if **shown == map => Arc::clone(shown),
            _ => Arc::new(map),
        };
        let scale = match previous {
            Some(Environment {
                source: EnvironmentSource::Map(_),
                scale,
                ..
            }) => *scale,
            _ => 1.0,
        };
        self.doc.setup.environment = Some(Environment {
            source: EnvironmentSource::Map(map),
            scale,
            rotation_deg: previous.map_or(0.0, |e| e.rotation_deg),
            background: previous.is_none_or(|e| e.background),
        });
        self.error = None;
        if !notes.is_empty() {
            self.notice = Some(notes.join("; "));
            self.doc.warnings.extend(notes);
        }
    }

    /// Whether an environment map is being read.
    pub fn loading_environment(&self) -> bool {
        self.loading_environment.is_some()
    }
}

/// `position` moved aside (along x, then z, inside `bounds` when it was inside) until no light
/// sits within a tenth of the scene's size of it.
pub fn beside_lights(
    position: [f32; 3],
    lights: &[Light],
    bounds: &tracer_core::geometry::Aabb,
) -> [f32; 3] {
    let step = (bounds.extent().max_element() * 0.15).max(1e-3);
    let start = glam::Vec3::from(position);
    let inside = |p: glam::Vec3| bounds.contains(&tracer_core::geometry::Aabb { min: p, max: p });
    let keep_inside = inside(start);
    let free = |p: glam::Vec3| {
        lights
            .iter()
            .all(|l| l.position().distance(p) >= step * (2.0 / 3.0))
    };
    if free(start) {
        return position;
    }
    for k in 1..=8 {
        let d = step * k as f32;
        for offset in [
            glam::Vec3::X * d,
            -glam::Vec3::X * d,
            glam::Vec3::Z * d,
            -glam::Vec3::Z * d,
        ] {
            let p = start + offset;
            if free(p) && (!keep_inside || inside(p)) {
                return p.to_array();
            }
        }
    }
    (start + glam::Vec3::X * step).to_array()
}
